// write_surface_vdb (engine/io/surface_files.hpp): the mesh as OpenVDB's narrow-band level set,
// what Houdini's and Blender's volume tools expect of a fluid surface (a signed distance,
// negative inside, grid class "level set"), rather than phi, whose values are not distances.
#include <cstdio>
#include <filesystem>
#include <mutex>

#include <fmt/format.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>

#include "engine/core/error.hpp"
#include "engine/io/surface_files.hpp"

namespace pbf {

void write_surface_vdb(const std::string& path, const SurfaceMesh& mesh, double voxel) {
  static std::once_flag initialised;
  std::call_once(initialised, [] { openvdb::initialize(); });
  std::vector<openvdb::Vec3s> points;
  points.reserve(mesh.mesh.vertices.size());
  for (const auto& v : mesh.mesh.vertices) points.emplace_back(float(v[0]), float(v[1]), float(v[2]));
  std::vector<openvdb::Vec3I> triangles;
  triangles.reserve(mesh.mesh.triangles.size());
  for (const auto& t : mesh.mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  const auto transform = openvdb::math::Transform::createLinearTransform(voxel);
  openvdb::FloatGrid::Ptr grid = triangles.empty()
                                     ? openvdb::createLevelSet<openvdb::FloatGrid>(voxel, 3.0)
                                     : openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(*transform, points, triangles, 3.0f);
  grid->setName("surface");
  grid->setGridClass(openvdb::GRID_LEVEL_SET);
  const std::string tmp = path + ".tmp";
  try {
    openvdb::io::File file(tmp);
    file.write({grid});
    file.close();
  } catch (const openvdb::Exception& e) {
    std::remove(tmp.c_str());
    throw Error(fmt::format("{}: cannot write the level set: {}", path, e.what()));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    throw Error(fmt::format("{}: cannot write: {}", path, ec.message()));
  }
}

}  // namespace pbf

#include "engine/io/vtp.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>

#include "engine/core/error.hpp"
#include "engine/io/vtk_appended.hpp"

namespace pbf {

void write_vtp(const std::string& path, const TriangleMesh& mesh, const std::vector<std::array<double, 3>>* velocity) {
  std::vector<VtuArray> arrays;
  if (velocity) {
    if (velocity->size() != mesh.vertices.size())
      throw Error(fmt::format("{}: {} velocities for {} vertices", path, velocity->size(), mesh.vertices.size()));
    arrays.push_back({"velocity", 3, VtuType::Float64, velocity->data()});
  }
  write_vtp(path, mesh, arrays);
}

void write_vtp(const std::string& path, const TriangleMesh& mesh, const std::vector<VtuArray>& point_data,
               const std::string& normals) {
  const std::size_t points = mesh.vertices.size(), polys = mesh.triangles.size();
  for (std::size_t t = 0; t < polys; ++t)
    for (std::uint32_t v : mesh.triangles[t])
      if (v >= points)
        throw Error(
            fmt::format("{}: triangle {} names vertex {}, but the surface has {} vertices", path, t, v, points));

  VtkAppendedFile out(path, "PolyData");
  out.head(
      fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" "
                  "NumberOfPolys=\"{}\">\n",
                  points, polys));
  if (!point_data.empty()) {
    std::string attributes;
    for (const VtuArray& a : point_data)
      if (a.components == 3 && a.name != normals && attributes.empty()) attributes = fmt::format(" Vectors=\"{}\"", xml_escape(a.name));
    if (!normals.empty()) attributes += fmt::format(" Normals=\"{}\"", xml_escape(normals));
    out.head(fmt::format("      <PointData{}>\n", attributes));
    for (const VtuArray& a : point_data)
      out.declare(type_name(a.type), a.name, a.components, points * a.components * type_size(a.type));
    out.head("      </PointData>\n");
  }
  out.head("      <Points>\n");
  out.declare("Float64", "Points", 3, points * 3 * sizeof(double));
  out.head("      </Points>\n      <Polys>\n");
  out.declare("Int64", "connectivity", 1, polys * 3 * 8);
  out.declare("Int64", "offsets", 1, polys * 8);
  out.head("      </Polys>\n    </Piece>\n");

  static_assert(sizeof(mesh.vertices[0]) == 3 * sizeof(double), "vertices are packed x, y, z");
  for (const VtuArray& a : point_data) out.block(a.data, points * a.components * type_size(a.type));
  out.block(mesh.vertices.data(), points * 3 * sizeof(double));
  // The indices widened to Int64 (what VTK's own writers use) in chunks, not materialised.
  constexpr std::size_t kChunk = 1024;
  std::int64_t ints[3 * kChunk];
  out.begin_block(polys * 3 * 8);
  for (std::size_t t = 0; t < polys; t += kChunk) {
    const std::size_t m = std::min(kChunk, polys - t);
    for (std::size_t k = 0; k < m; ++k)
      for (int c = 0; c < 3; ++c) ints[3 * k + c] = mesh.triangles[t + k][c];
    out.write(ints, m * 3 * 8);
  }
  out.begin_block(polys * 8);  // where each polygon ends in connectivity: 3, 6, 9, ...
  for (std::size_t t = 0; t < polys; t += kChunk) {
    const std::size_t m = std::min(kChunk, polys - t);
    for (std::size_t k = 0; k < m; ++k) ints[k] = static_cast<std::int64_t>(3 * (t + k + 1));
    out.write(ints, m * 8);
  }
  out.commit();
}

}  // namespace pbf

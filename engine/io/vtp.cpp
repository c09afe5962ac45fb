#include "engine/io/vtp.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>

#include "engine/core/error.hpp"
#include "engine/io/vtk_appended.hpp"

namespace pbf {

void write_vtp(const std::string& path, const TriangleMesh& mesh, const std::vector<std::array<double, 3>>* velocity) {
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
  if (velocity) {
    if (velocity->size() != points)
      throw Error(fmt::format("{}: {} velocities for {} vertices", path, velocity->size(), points));
    out.head("      <PointData Vectors=\"velocity\">\n");
    out.declare("Float64", "velocity", 3, points * 3 * sizeof(double));
    out.head("      </PointData>\n");
  }
  out.head("      <Points>\n");
  out.declare("Float64", "Points", 3, points * 3 * sizeof(double));
  out.head("      </Points>\n      <Polys>\n");
  out.declare("Int64", "connectivity", 1, polys * 3 * 8);
  out.declare("Int64", "offsets", 1, polys * 8);
  out.head("      </Polys>\n    </Piece>\n");

  static_assert(sizeof(mesh.vertices[0]) == 3 * sizeof(double), "vertices are packed x, y, z");
  if (velocity) out.block(velocity->data(), points * 3 * sizeof(double));
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

#pragma once
// A solid's surface as a VTK XML PolyData file (.vtp): the vertices as Points and each
// triangle as a polygon (Polys: connectivity and offsets), in the appended binary layout of
// the particle frames (engine/io/vtk_appended.hpp), so ParaView shows solids beside them.
#include <string>
#include <vector>

#include "engine/geometry/triangle_mesh.hpp"
#include "engine/io/vtu.hpp"

namespace pbf {

// Writes `mesh` to `path` (through PATH.tmp and a rename), with `velocity` (m/s, one per
// vertex: a body's point velocities) as PointData when given. Throws pbf::Error naming the
// path if a triangle names a vertex the mesh does not have, or if the file cannot be written.
void write_vtp(const std::string& path, const TriangleMesh& mesh, const std::vector<std::array<double, 3>>* velocity = nullptr);
// The same with any PointData arrays (each vertices.size() * components values, interleaved);
// the one named `normals`, if any, is declared as the vertices' normals (smooth shading).
void write_vtp(const std::string& path, const TriangleMesh& mesh, const std::vector<VtuArray>& point_data,
               const std::string& normals = "");

}  // namespace pbf

#pragma once
// Triangle meshes from files (OBJ, STL and whatever else Assimp reads), their placement and
// bounds. Whether one bounds a solid, and which way it faces: mesh_surface.hpp.
#include <array>
#include <cstddef>
#include <string>

#include "engine/geometry/triangle_mesh.hpp"

namespace pbf {

// Reads a mesh file. Errors name it: "mesh file 'PATH': cannot be read (REASON)" for a
// missing or unreadable file, else those of read_mesh_memory.
TriangleMesh read_mesh_file(const std::string& path);

// Reads a mesh from bytes through Assimp; `name` is what errors call it, `extension_hint`
// ("obj", "stl", ...; a leading dot is ignored) picks the reader first, and the contents pick
// one when it does not fit. No other file is opened: an OBJ's materials are not read (a
// solid needs none), and a glTF must hold its buffers (.glb, or data URIs). Polygons are
// split into triangles; points and lines are dropped; every mesh of the file is taken, at
// every place its nodes put it (a mirroring node's triangles reversed). Vertices at the
// same position are joined (the closedness check needs shared vertices, which STL lacks).
// Refused: an empty or unparseable file, no triangles, coordinates that are not finite or
// beyond 1e6 m, indices out of range, degenerate (zero-area) triangles, over 1 GiB.
TriangleMesh read_mesh_memory(const void* data, std::size_t size, const std::string& name,
                              const std::string& extension_hint);

// The rotation of a Placement, row-major: R = Rz * Ry * Rx (degrees about the fixed x, then
// y, then z axes). Multiples of 90 degrees give exact zeros and ones.
std::array<double, 9> rotation_matrix(const std::array<double, 3>& rotate_deg);

// Scales about the origin, rotates (rotation_matrix), then translates. A mirroring scale (an
// odd number of negative factors) reverses every triangle, so the surface keeps facing out.
void place(TriangleMesh& mesh, const Placement& placement);

// The smallest box holding every vertex: {lo, hi}; lo > hi (infinities) when there is none.
std::array<std::array<double, 3>, 2> bounds(const TriangleMesh& mesh);

}  // namespace pbf

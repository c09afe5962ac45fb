#pragma once
// A solid for the output tests, independent of the `solid` style: a fix that holds a mesh and
// shows it to the outputs, with a version the test bumps when it moves the mesh.
#include <array>
#include <cstdint>
#include <string>
#include <utility>

#include "engine/core/fix.hpp"
#include "engine/geometry/solid_body.hpp"

namespace pbf::test {

// The box [lo, hi]: 8 corners (corner k has x from bit 0, y from bit 1, z from bit 2) and 12
// triangles, counter-clockwise seen from outside.
inline TriangleMesh box_mesh(const std::array<double, 3>& lo, const std::array<double, 3>& hi) {
  TriangleMesh m;
  for (int k = 0; k < 8; ++k)
    m.vertices.push_back({k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]});
  // One quad per face, corners counter-clockwise seen from outside; two triangles each.
  const std::uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                     {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  return m;
}

class TestSolid : public Fix, public SolidBody {
 public:
  TestSolid(const std::string& id, TriangleMesh mesh, bool container)
      : Fix(id, "test/solid"), mesh_(std::move(mesh)), container_(container) {}

  std::vector<Stage> stages() const override { return {}; }
  const SolidBody* solid_body() const override { return this; }
  const std::string& name() const override { return id(); }
  const TriangleMesh& surface() const override { return mesh_; }
  std::uint64_t surface_version() const override { return version_; }
  bool fluid_inside() const override { return container_; }

  // Moves the surface up by dz: a new version.
  void lift(double dz) {
    for (auto& v : mesh_.vertices) v[2] += dz;
    ++version_;
  }

 private:
  TriangleMesh mesh_;
  bool container_;
  std::uint64_t version_ = 0;
};

}  // namespace pbf::test

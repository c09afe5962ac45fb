#include "engine/geometry/mesh_sdf.hpp"

#include <cmath>
#include <mutex>
#include <omp.h>
#include <vector>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/MeshToVolume.h>

namespace pbf {

namespace {

class MeshShape final : public Shape {
 public:
  MeshShape(openvdb::FloatGrid::Ptr grid, double band) : grid_(std::move(grid)), band_(band) {
    // One accessor per OpenMP thread: an accessor caches the path to the last voxel it read,
    // which makes neighbouring lookups fast, and must not be shared between threads.
    for (int t = 0; t < omp_get_max_threads(); ++t) accessors_.emplace_back(grid_->getConstAccessor());
  }
  double signed_distance(const Point& p) const override {
    auto& accessor = accessors_[static_cast<std::size_t>(omp_get_thread_num()) % accessors_.size()];
    const openvdb::Vec3R index = grid_->transform().worldToIndex(openvdb::Vec3R(p[0], p[1], p[2]));
    float value;
    openvdb::tools::BoxSampler::sample(accessor, index, value);
    return double(value);
  }
  double reach() const override { return band_; }
  double grid_cell() const override { return grid_->voxelSize()[0]; }

 private:
  openvdb::FloatGrid::Ptr grid_;
  mutable std::vector<openvdb::FloatGrid::ConstAccessor> accessors_;
  double band_;
};

}  // namespace

std::unique_ptr<Shape> mesh_shape(const TriangleMesh& mesh, double voxel, double band) {
  static std::once_flag initialised;
  std::call_once(initialised, [] { openvdb::initialize(); });
  std::vector<openvdb::Vec3s> points;
  points.reserve(mesh.vertices.size());
  for (const auto& v : mesh.vertices) points.emplace_back(float(v[0]), float(v[1]), float(v[2]));
  std::vector<openvdb::Vec3I> triangles;
  triangles.reserve(mesh.triangles.size());
  // OpenVDB's interior is where the triangles' normals point away from; ours point outward too.
  for (const auto& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  const auto transform = openvdb::math::Transform::createLinearTransform(voxel);
  const float half_width = float(std::ceil(band / voxel) + 1);
  auto grid = openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(*transform, points, triangles, half_width);
  return std::make_unique<MeshShape>(grid, (half_width - 1) * voxel);
}

}  // namespace pbf

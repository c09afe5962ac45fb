#pragma once
// The signed distance of a closed triangle mesh, from OpenVDB's mesh-to-level-set conversion
// (exact distances to the nearest triangle at the voxels of a narrow band, the sign of the
// interior flood-filled beyond it), sampled trilinearly.
#include <memory>

#include "engine/geometry/shape.hpp"

namespace pbf {

// `mesh` must be closed and oriented outward (engine/geometry/mesh_surface.hpp:
// orient_surface). Distances are exact to within float rounding up to `band` from the
// surface, on a grid of spacing `voxel` whose nodes sit at integer multiples of it.
std::unique_ptr<Shape> mesh_shape(const TriangleMesh& mesh, double voxel, double band);

}  // namespace pbf

#pragma once
// Where a particle's path over a step meets a solid's surface, from the solid's map
// (engine/geometry/solid_map.hpp), in the frame the map was built in: the projection of the
// `solid` fix (engine/fixes/solid.cpp).
#include "engine/core/real.hpp"
#include "engine/geometry/solid_map.hpp"

namespace pbf {

enum class Contact { none, moved, lost };

// Where projection puts a particle: `gap` in front of the surface; `hair`, the map's rounding
// allowed for (a particle within gap + hair of it touches it); `min_step`, the shortest step
// of the march along a path.
struct ContactDistances {
  real hair, gap, min_step;
};

// Whether a particle that started the step `start_distance` from the wall and has moved
// `moved` since is still farther than `reach` from it, without a lookup: a distance changes
// no faster than the position (|grad d| = 1), and 1.25 allows for the map's spline. Most of
// the fluid is far from the walls, and this spares it the map in every projection.
inline bool far_from_wall(real start_distance, real moved, real reach) {
  return real(1.25) * moved < start_distance - reach;
}

// Moves p out of the wall along the path the particle took this step from p0, where it
// started at `start_distance` from the wall: to the first point of the path at the surface,
// less the motion into the wall there, then `gap` in front of it. Lost when the particle is
// deep inside the wall, which projection cannot undo.
Contact keep_out(const SolidMap& map, const ContactDistances& at, const real p0[3], real start_distance, real p[3]);

}  // namespace pbf

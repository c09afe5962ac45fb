#pragma once
// The simulation box: axis-aligned, z up. Walls, if any, are fixes; the domain only says
// where particles may be at the end of a step and bounds the neighbour grid.
#include "engine/core/real.hpp"

namespace pbf {

struct Domain {
  double lo[3] = {0, 0, 0};
  double hi[3] = {1, 1, 1};
  // Axes along which the domain repeats: a particle that leaves through one face comes back
  // through the opposite one, and pairs see each other across the faces.
  bool periodic[3] = {false, false, false};

  // Compared in the particle data's precision, as walls clamp positions to real(lo), real(hi).
  bool contains(real x, real y, real z) const {
    return x >= real(lo[0]) && x <= real(hi[0]) && y >= real(lo[1]) && y <= real(hi[1]) && z >= real(lo[2]) &&
           z <= real(hi[2]);
  }
  double extent(int axis) const { return hi[axis] - lo[axis]; }
};

}  // namespace pbf

#pragma once
// The simulation box: axis-aligned, z up. Walls, if any, are fixes; the domain only says
// where particles may be at the end of a step and bounds the neighbour grid.
//
// A periodic axis repeats with period L = real(hi - lo) (the one convention for an image
// everywhere: computed once in double, rounded once to the particles' precision): particle
// j's images sit at x_j +/- L, each coordinate the sum of two reals rounded once, the same on
// every rank. Positions wrap into [real(lo), real(hi)) at the start of each step
// (wrap_periodic); within a step a particle may cross a face, so along a periodic axis the
// domain holds [lo - L, hi + L].
//
// An open face (2 a for the lower face of axis a, 2 a + 1 for the upper; the box fix's `open`)
// lets particles out: one that crosses it leaves the run at the next step's start (the
// exchange stage), so until then the domain holds it on the far side too.
#include "engine/core/real.hpp"

namespace pbf {

struct Domain {
  double lo[3] = {0, 0, 0};
  double hi[3] = {1, 1, 1};
  // Axes along which the domain repeats: a particle that leaves through one face comes back
  // through the opposite one, and pairs see each other across the faces.
  bool periodic[3] = {false, false, false};
  // Faces particles leave the run through (set from the box fix at each run's start).
  bool open[6] = {false, false, false, false, false, false};

  bool any_periodic() const { return periodic[0] || periodic[1] || periodic[2]; }
  // The offset of an image along a periodic axis.
  real period(int axis) const { return real(hi[axis] - lo[axis]); }
  // The coordinate of the image `shift` periods (-1, 0 or 1) away: one rounding.
  real image(int axis, real v, int shift) const {
    return shift > 0 ? v + period(axis) : (shift < 0 ? v - period(axis) : v);
  }

  // Compared in the particle data's precision, as walls clamp positions to real(lo), real(hi).
  bool contains(real x, real y, real z) const { return along(0, x) && along(1, y) && along(2, z); }
  bool along(int axis, real v) const {
    if (!periodic[axis]) return (open[2 * axis] || v >= real(lo[axis])) && (open[2 * axis + 1] || v <= real(hi[axis]));
    const real L = period(axis);
    return v >= real(lo[axis]) - L && v <= real(hi[axis]) + L;
  }
  double extent(int axis) const { return hi[axis] - lo[axis]; }
  // Whether a point lies beyond an open face (and leaves the run at the next step's start).
  bool beyond_open_face(real x, real y, real z) const {
    const real p[3] = {x, y, z};
    for (int a = 0; a < 3; ++a)
      if ((open[2 * a] && p[a] < real(lo[a])) || (open[2 * a + 1] && p[a] > real(hi[a]))) return true;
    return false;
  }

  // The coordinate along a periodic axis moved by one period into [real(lo), real(hi)): at
  // most one period (a step moves a particle less, the end-of-step check holds it to that),
  // and a result the rounding of v -/+ L leaves outside goes to the face lo, so that wrapping
  // a wrapped coordinate changes nothing (a restart's run start wraps again).
  real wrapped(int axis, real v) const {
    const real low = real(lo[axis]), high = real(hi[axis]);
    if (v >= high) v -= period(axis);
    else if (v < low) v += period(axis);
    else return v;
    return v >= low && v < high ? v : low;
  }
};

}  // namespace pbf

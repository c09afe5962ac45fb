#pragma once
// Filling a box region with particles on a cubic lattice.
#include <cstddef>

namespace pbf {

class Simulation;

class Shape;

// Particles at lo + (i + 1/2) s along each axis while inside [lo, hi] (and, if `inside` is
// given, inside that shape: a drop, water filling a closed mesh), with the given velocity and
// the lattice mass rule (engine/mass.hpp). Returns how many were added.
std::size_t add_lattice(Simulation& sim, const double lo[3], const double hi[3], double spacing,
                        const double velocity[3], const Shape* inside = nullptr);

}  // namespace pbf

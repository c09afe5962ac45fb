#pragma once
// Particles that start on top of one another (two lattices on the same sites, a file listing a
// point twice). The kernel gradient between two particles at one point is zero (gradW = g(r)
// r_vec with r_vec = 0), so neither solver can push them apart: they see the same neighbours,
// get the same corrections or forces, and move as one particle of twice the mass for ever.
// The first run (from step 0: the run loop) therefore starts by moving them apart, by a rule
// of positions and ids alone (never of memory order or thread count):
//
//   close:  |x_i - x_j| < kCoincident h
//   rank_i: the number of particles close to i with a smaller id (0: i stays where it is)
//   move:   x_i += kApart h (1 + floor((rank_i - 1) / 12)) d_k,   k = (rank_i - 1) mod 12,
//           d_k the k-th of the 12 directions to an icosahedron's vertices (each next to its
//           opposite), a component flipped where it would leave the domain
//
// The ranks are taken before anything moves, so the rule is a function of the start state. A
// group of m coincident particles keeps its lowest id in place and spreads the other m - 1
// over distinct points at least kApart h from it and from one another. Half a kernel radius
// (a spacing at h = 2 s) takes a duplicate out of the core of its partner's kernel: inside a
// lattice an extra particle then weighs about 1.4 rho0 wherever it lands (the lattice's rho0
// and its own m W(0)), against 1.8 rho0 for a triple 0.1 h apart, beyond WCSPH's limit.
#include <cstddef>

namespace pbf {

class Simulation;

inline constexpr double kCoincident = 0.01;  // in h: "on top of one another" below this distance
inline constexpr double kApart = 0.5;        // in h: how far a coincident particle is moved

// Moves coincident particles apart as above, over the neighbour lists at the current
// positions (built if stale), and returns how many it moved; logs one warning giving the
// count when it moved any.
std::size_t separate_coincident(Simulation& sim);

}  // namespace pbf

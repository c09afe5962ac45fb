#pragma once
// The resolution of a scene: the particle spacing s against the kernel radius h. SPH needs a
// kernel that reaches a few particles: h below s leaves a particle without neighbours (the
// density is its own mass alone and the solver has nothing to push against), and h far above
// s gives each particle thousands of neighbours, so the neighbour lists and the mass rule's
// lattice sums grow as (h/s)^3 without making the fluid more accurate. Refused outside
// 1..10 spacings; a warning outside 1.5..4, the range the solvers are tuned and tested for.
#include <cstddef>
#include <string>

#include "engine/core/real.hpp"

namespace pbf {

inline constexpr double kMinSpacings = 1, kMaxSpacings = 10;       // refused outside
inline constexpr double kUsualMinSpacings = 1.5, kUsualMaxSpacings = 4;  // a warning outside

// The median distance from a particle to its nearest neighbour, over up to 256 particles
// spread evenly through the list (all of them when there are fewer), each compared with
// every particle: h plays no part, so a wrong h cannot make the estimate explode. 0 for
// fewer than two particles.
double sampled_spacing(const real* x, const real* y, const real* z, std::size_t n);
// The same over this process's share of a set; in a distributed run the least of the shares'
// (a share's is never below the whole set's), 0 where none has two particles. Collective there.
double sampled_spacing_of_shares(const real* x, const real* y, const real* z, std::size_t n, bool distributed);

// Throws when h is outside 1..10 spacings, warns outside 1.5..4; `what` names the source
// of the particles (pbf.lattice, a file) in the message.
void check_kernel_radius(double h, double spacing, const std::string& what);

}  // namespace pbf

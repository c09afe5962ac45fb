#pragma once
// The inlet zone of an emitter (engine/fixes/emitter.cpp, `buffer` > 0), for an opening
// under water or at a wall, where the fluid ahead would block the opening's particles: the
// zone's particles (those over the opening from s/2 behind its plane to `buffer` ahead of it at
// a step's start) move kinematically through that step, whatever the solver does to them,
//   x = x0 + U_k dt,   v = U_k           (U_k: the velocity of the site whose cell they are over),
// set after each of the solver's corrections and after the velocity update. The zone is a piston of fluid: its particles still count in
// their neighbours' densities and pressures, so the fluid ahead is pushed at the set rate, and
// a particle that crosses the zone's front goes on as fluid. The emitter's particles enter at
// the back of the zone L behind the hindmost (find_back), so the inflow is the set one however
// deep the water ahead: DualSPHysics's inlet buffer, whose particles are moved by the imposed
// velocity alone (its zone lies outside the fluid); here they are fluid that joins the solver
// once it leaves the zone. The zone's particles are marked in a field ("inlet_<id>", saved in
// restarts, carried between ranks): those that entered through the opening, and those in the
// zone when the inlet opened; water that comes in from beside is no member.
#include <array>
#include <cstdint>
#include <vector>

#include "engine/core/particles.hpp"
#include "engine/fixes/emitter_opening.hpp"

namespace pbf {

class InletZone {
 public:
  // At the step's start, before the emitter's particles enter: each site's D_k, the offset
  // along n of its hindmost zone particle (L for a cell with none: one enters at the plane at
  // once), on every rank's particles. A particle enters L behind it as soon as D_k >= L, never
  // waiting: the zone stays full, its particles L apart along n, and moves at U_k, so the rate
  // is the set one. `first`: the inlet's first step, when the fluid in the zone joins it.
  // At the step's start, after migration and reordering (the indices hold until its end): the
  // members (member[i] = 1) within [-behind, depth) of the opening along its normal, over it,
  // and where they are; members elsewhere have left the zone (member[i] = 0). Fluid that comes
  // into the zone from beside it is no member: the solver moves it, and the zone pushes it out.
  void take(Particles& P, const Opening& opening, double behind, double depth, FieldId member);
  std::size_t size() const { return index_.size(); }
  void find_back(Particles& P, const Opening& opening, double behind, double depth, FieldId member, bool first,
                 double L, std::vector<double>& D) const;
  void clear() { index_.clear(), site_.clear(), start_.clear(); }
  // Each at x0 + U dt (U: its site's velocity): after each of the solver's corrections (PBF's
  // iterations: the zone is a moving boundary to the fluid beside and ahead of it, as the
  // box's walls are), and after the velocity update, with the velocity U (`with_velocity`).
  void move(Particles& P, const std::vector<std::array<real, 3>>& site_velocity, double dt,
            bool with_velocity) const;

 private:
  // Kept from step to step (a step allocates nothing once they have grown).
  std::vector<std::uint32_t> index_, site_;
  std::vector<std::array<real, 3>> start_;
};

}  // namespace pbf

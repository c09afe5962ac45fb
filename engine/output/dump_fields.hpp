#pragma once
// The per-particle quantities a dump can write, by name: every declared field (position,
// velocity, mass, and whatever the pipeline's fixes add, such as lambda or vorticity), the
// particle id, and quantities derived when the frame is written: density and density_error
// (rho/rho0 - 1) of the density the solver uses (Simulation::solver_density: wcsph's own
// density field, else the SPH sum), summed_density (the SPH sum with walls, which differs
// from the solver's under wcsph's continuity density), speed (|v|) and vorticity_magnitude
// (|curl v|). Values come out in id order, the order of the input, so frames of one run line
// up particle by particle.
#include <cstdint>
#include <string>
#include <vector>

#include "engine/registry/params.hpp"
#include "engine/core/real.hpp"

namespace pbf {

class Simulation;

class DumpFields {
 public:
  explicit DumpFields(Names names) : names_(std::move(names)) {}

  // Checks the names against what the simulation has now (in the dump's init, after the
  // other fixes declared their fields); an unknown name is an error listing the valid ones.
  void resolve(const Simulation& sim);
  static std::vector<std::string> valid_names(const Simulation& sim);

  const Names& names() const { return names_; }
  std::size_t size() const { return names_.size(); }
  int components(std::size_t k) const { return components_[k]; }
  bool is_id(std::size_t k) const { return names_[k] == "id"; }
  // Unit and meaning, for colour bars and file headers.
  std::string unit(std::size_t k) const;

  // Field k's values for particles in id order, components interleaved (n * components).
  // Derived quantities are computed afresh (density refreshes the neighbour lists).
  void gather(Simulation& sim, std::size_t k, std::vector<real>& out);
  // Field k's components, one value per particle of this rank in memory order (valid until the
  // next call). Collective in a distributed run (derived fields read neighbours).
  std::vector<const real*> columns(Simulation& sim, std::size_t k);
  // The ids in the order gather() gives the values: ascending.
  void gather_ids(const Simulation& sim, std::vector<std::int64_t>& out) const;

 private:
  Names names_;
  std::vector<int> components_;
  std::vector<std::vector<real>> scratch_;  // per field: derived values
};

}  // namespace pbf

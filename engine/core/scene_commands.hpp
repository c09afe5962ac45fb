#pragma once
// The scene commands both bindings give (Lua's pbf.domain, pbf.lattice, pbf.delete; the
// Python module's Simulation.domain, lattice, delete): their schemas and what they do, here
// once, so that a scene built from either checks its values the same way and says the same.
// `what` names the command in messages ("pbf.lattice" from Lua, "lattice" from Python).
#include <cstddef>
#include <string>
#include <vector>

#include "engine/core/domain.hpp"
#include "engine/registry/params.hpp"

namespace pbf {

class Simulation;

std::vector<ParamSpec> domain_params();
// The domain the checked parameters describe.
Domain domain_from(const Params& p);

// lo, hi, spacing, velocity; or a sphere (center, radius) or a closed mesh to fill (mesh,
// orient, scale, rotate, translate). A velocity given as a function of place is the
// binding's to apply after (it knows how to call the script's function).
std::vector<ParamSpec> lattice_params();
struct LatticeAdded {
  std::size_t first = 0;  // this rank's index of the first particle added
  std::size_t added = 0;  // added on every rank together
};
LatticeAdded lattice_command(Simulation& sim, const Params& p, const char* what);

// Removes the particles inside a region (engine/geometry/region.hpp); returns how many (on
// every rank together). The others keep their ids.
std::vector<ParamSpec> delete_params();
std::size_t delete_command(Simulation& sim, const Params& p);

class Compute;
// The compute `id`, checked ready to evaluate now (there are particles; it runs on several
// ranks if the run does); `what` names the asking command ("pbf.value").
Compute& compute_to_evaluate(Simulation& sim, const std::string& id, const char* what);

}  // namespace pbf

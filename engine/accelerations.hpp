#pragma once
// Styles that add accelerations need a fix that integrates them (leapfrog), and a solver
// that moves positions itself (pbf) must not run beside one: one check, for them all.
#include <string>

namespace pbf {

class Simulation;

// Whether some fix of the pipeline integrates accelerations.
bool has_integrator(const Simulation& sim);
// Throws unless some fix integrates accelerations (`who` names the caller in the error).
void require_integrator(const Simulation& sim, const std::string& who);
// Throws if some fix integrates accelerations.
void forbid_integrator(const Simulation& sim, const std::string& who);

}  // namespace pbf

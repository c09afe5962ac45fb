#include "engine/accelerations.hpp"

#include <fmt/format.h>

#include "engine/error.hpp"
#include "engine/simulation.hpp"

namespace pbf {

namespace {
const Fix* integrator(const Simulation& sim) {
  for (const auto& f : sim.fixes())
    if (f->integrates_accelerations()) return f.get();
  return nullptr;
}
}  // namespace

bool has_integrator(const Simulation& sim) { return integrator(sim) != nullptr; }

void require_integrator(const Simulation& sim, const std::string& who) {
  if (!integrator(sim))
    throw Error(fmt::format("{} adds accelerations, but no fix integrates them: add pbf.fix(\"integrator\", "
                            "\"leapfrog\", {{}})", who));
}

void forbid_integrator(const Simulation& sim, const std::string& who) {
  if (const Fix* f = integrator(sim))
    throw Error(fmt::format("{} moves particles itself and cannot run beside fix '{}' ({}), which integrates "
                            "accelerations: use one solver", who, f->id(), f->style()));
}

}  // namespace pbf

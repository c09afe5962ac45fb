// flow: what one fix has let into the scene (an emitter) or out of it (an outflow, a box's
// open faces) since the scene began: the number of particles and their mass, summed exactly
// (engine/core/particle_flow.hpp), so that initial + in - out = present holds for a scene.
#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/core/names.hpp"
#include "engine/core/particle_flow.hpp"
#include "engine/core/simulation.hpp"
#include "engine/registry/builtin_styles.hpp"

namespace pbf {

namespace {

class Flow : public Compute {
 public:
  Flow(const std::string& id, const Params& p) : Compute(id, "flow"), fix_(p.string("fix")) {}
  std::vector<std::string> names() const override { return {"count", "mass"}; }
  std::vector<std::string> units() const override { return {"-", "kg"}; }
  bool runs_distributed() const override { return true; }  // the tally is every rank's
  void evaluate(Simulation& sim, std::vector<double>& values) override {
    const ParticleFlow* flow = find(sim);
    values = {static_cast<double>(flow->count()), flow->mass()};
  }

 private:
  const ParticleFlow* find(const Simulation& sim) const {
    std::vector<std::string> passing;
    for (const auto& f : sim.fixes())
      if (f->particle_flow()) passing.push_back(f->id());
    const Fix* fix = sim.find_fix(fix_);
    if (!fix)
      throw Error(fmt::format("compute '{}' (flow): no fix '{}'{}", id(), fix_,
                              passing.empty() ? std::string(" (no fix adds or removes particles)")
                                              : did_you_mean(fix_, passing)));
    if (!fix->particle_flow())
      throw Error(fmt::format("compute '{}' (flow): fix '{}' ({}) adds and removes no particles (those that do: {})",
                              id(), fix_, fix->style(), passing.empty() ? "none" : fmt::format("{}", fmt::join(passing, ", "))));
    return fix->particle_flow();
  }
  std::string fix_;
};

}  // namespace

void register_compute_flow(StyleRegistry& r) {
  r.add({"flow", StyleKind::compute,
         "particles and mass a fix has let in (emitter) or out (outflow, open faces) since the scene began",
         {{"fix", ParamType::String, std::nullopt, "", "the id of the emitter, outflow or box with open faces"}},
         nullptr, make_compute<Flow>(), "`count` (-), `mass` (kg)"});
}

}  // namespace pbf

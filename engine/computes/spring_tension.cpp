// spring_tension: what a `spring` fix pulls with now: its tension (N; positive when stretched), its
// length (m) and the force on its body fx, fy, fz (N; the anchor, or the other body, takes the
// opposite): a mooring line's load.
#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/core/names.hpp"
#include "engine/core/simulation.hpp"
#include "engine/fixes/spring.hpp"
#include "engine/registry/builtin_styles.hpp"

namespace pbf {

namespace {

class Spring : public Compute {
 public:
  Spring(const std::string& id, const Params& p) : Compute(id, "spring_tension"), fix_(p.string("fix")) {}
  std::vector<std::string> names() const override { return {"tension", "length", "fx", "fy", "fz"}; }
  std::vector<std::string> units() const override { return {"N", "m", "N", "N", "N"}; }
  bool runs_distributed() const override { return true; }  // every rank has the same bodies
  void evaluate(Simulation& sim, std::vector<double>& values) override {
    std::vector<std::string> springs;
    for (const auto& f : sim.fixes())
      if (dynamic_cast<const SpringFix*>(f.get())) springs.push_back(f->id());
    const auto* spring = dynamic_cast<const SpringFix*>(sim.find_fix(fix_));
    if (!spring)
      throw Error(fmt::format("compute '{}' (spring_tension): no spring '{}'{}", id(), fix_,
                              springs.empty() ? std::string(" (the pipeline has none)") : did_you_mean(fix_, springs)));
    const SpringFix::State s = spring->state();
    values = {s.tension, s.length, s.force[0], s.force[1], s.force[2]};
  }

 private:
  std::string fix_;
};

}  // namespace

void register_compute_spring(StyleRegistry& r) {
  r.add({"spring_tension",
         StyleKind::compute,
         "a spring's tension, length and force on its body",
         {{"fix", ParamType::String, std::nullopt, "", "the spring's fix id"}},
         nullptr, make_compute<Spring>(),
         "`tension` (N), `length` (m), `fx`, `fy`, `fz` (N, on its body)"});
}

}  // namespace pbf

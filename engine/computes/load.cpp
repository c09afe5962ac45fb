// load: what the fluid exerts on one solid, averaged over the last step: the force fx, fy,
// fz (N) and the torque tx, ty, tz (N m) about a point (`about`, default the origin). The
// solid adds up the momentum its wall terms gave the fluid (density gradient, projection,
// velocity corrections) and reports the opposite (docs/physics.md, "Loads on solids").
#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/core/names.hpp"
#include "engine/core/simulation.hpp"
#include "engine/registry/builtin_styles.hpp"

namespace pbf {

namespace {

class Load : public Compute {
 public:
  Load(const std::string& id, const Params& p) : Compute(id, "load"), solid_(p.string("solid")), about_(p.vec3("about")) {}
  std::vector<std::string> names() const override { return {"fx", "fy", "fz", "tx", "ty", "tz"}; }
  std::vector<std::string> units() const override { return {"N", "N", "N", "N m", "N m", "N m"}; }
  bool runs_distributed() const override { return true; }  // the solid's load is every rank's
  void evaluate(Simulation& sim, std::vector<double>& values) override {
    const SolidBody* body = nullptr;
    std::vector<std::string> names;
    for (const SolidBody* s : sim.solid_bodies()) {
      names.push_back(s->name());
      if (s->name() == solid_) body = s;
    }
    if (!body)
      throw Error(fmt::format("compute '{}' (load): no solid '{}' in the pipeline{}", id(), solid_,
                              names.empty() ? std::string(" (it has none)") : did_you_mean(solid_, names)));
    const auto l = body->load();
    // The torque about `about`: T_c = T_0 - c x F.
    const double* c = about_.data();
    values = {l[0], l[1], l[2], l[3] - (c[1] * l[2] - c[2] * l[1]), l[4] - (c[2] * l[0] - c[0] * l[2]),
              l[5] - (c[0] * l[1] - c[1] * l[0])};
  }

 private:
  std::string solid_;
  Vec3 about_;
};

}  // namespace

void register_compute_load(StyleRegistry& r) {
  r.add({"load",
         StyleKind::compute,
         "force and torque the fluid exerts on a solid over the last step: fx, fy, fz (N), tx, ty, tz (N m)",
         {{"solid", ParamType::String, std::nullopt, "", "the solid's fix id"},
          ParamSpec{"about", ParamType::Vector3, Vec3{0, 0, 0}, "m", "the point torques are taken about"}
              .magnitude_at_most(1e6)},
         nullptr, make_compute<Load>(),
         "`fx`, `fy`, `fz` (N), `tx`, `ty`, `tz` (N m)"});
}

}  // namespace pbf

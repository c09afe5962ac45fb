// body: the state of a body the fluid moves (a `solid` with a density or a mass): its centre
// of mass x, y, z (m), its velocity vx, vy, vz (m/s), its turn since the scene placed it as a
// rotation vector rx, ry, rz (degrees: the axis times the angle; for small turns, the turns
// about x, y and z), its angular velocity wx, wy, wz (rad/s), and the fluid's load on it over
// the last step, the force fx, fy, fz (N) and the torque about its centre tx, ty, tz (N m); the
// force its held axes or hinge exerted over the step hx, hy, hz (N: a hinge's reaction), and
// the contacts' cx, cy, cz (N: what the floor bears).
#include <cmath>
#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/core/names.hpp"
#include "engine/core/simulation.hpp"
#include "engine/fixes/solid_dynamics.hpp"
#include "engine/registry/builtin_styles.hpp"

namespace pbf {

namespace {

class Body : public Compute {
 public:
  Body(const std::string& id, const Params& p) : Compute(id, "body"), solid_(p.string("solid")) {}
  std::vector<std::string> names() const override {
    return {"x",  "y",  "z",  "vx", "vy", "vz", "rx", "ry", "rz", "wx", "wy", "wz",
            "fx", "fy", "fz", "tx", "ty", "tz", "hx", "hy", "hz", "cx", "cy", "cz"};
  }
  std::vector<std::string> units() const override {
    return {"m", "m", "m", "m/s", "m/s", "m/s", "deg", "deg", "deg", "rad/s", "rad/s", "rad/s",
            "N", "N", "N", "N m", "N m", "N m", "N", "N", "N", "N", "N", "N"};
  }
  bool runs_distributed() const override { return true; }  // every rank has the same body
  void evaluate(Simulation& sim, std::vector<double>& values) override {
    const SolidDynamics* body = nullptr;
    std::vector<std::string> names;
    for (const SolidBody* s : sim.solid_bodies()) {
      if (s->dynamics()) names.push_back(s->name());
      if (s->name() == solid_) {
        body = s->dynamics();
        if (!body)
          throw Error(fmt::format("compute '{}' (body): solid '{}' is no body the fluid moves (give it a density or "
                                  "a mass); its load is compute 'load'",
                                  id(), solid_));
      }
    }
    if (!body)
      throw Error(fmt::format("compute '{}' (body): no body '{}' in the pipeline{}", id(), solid_,
                              names.empty() ? std::string(" (it has none)") : did_you_mean(solid_, names)));
    const RigidBody& b = body->body();
    const auto x = b.position(), v = b.velocity(), r = body->rotation(), w = b.angular_velocity();
    const auto load = body->fluid_load();
    const double deg = 180 / M_PI;
    values = {x[0], x[1], x[2], v[0], v[1], v[2], r[0] * deg, r[1] * deg, r[2] * deg, w[0], w[1], w[2]};
    values.insert(values.end(), load.begin(), load.end());
    for (const auto& f : {body->held_force(), body->contact_force()}) values.insert(values.end(), f.begin(), f.end());
  }

 private:
  std::string solid_;
};

}  // namespace

void register_compute_body(StyleRegistry& r) {
  r.add({"body",
         StyleKind::compute,
         "a body the fluid moves: centre, velocity, turn, angular velocity, and the fluid's force and torque on it",
         {{"solid", ParamType::String, std::nullopt, "", "the body's solid fix id"}},
         nullptr, make_compute<Body>(),
         "`x`, `y`, `z` (m), `vx`, `vy`, `vz` (m/s), `rx`, `ry`, `rz` (deg, the turn since placed as a rotation "
         "vector), `wx`, `wy`, `wz` (rad/s), `fx`, `fy`, `fz` (N), `tx`, `ty`, `tz` (N m, about the centre), `hx`, "
         "`hy`, `hz` (N, the held axes' or hinge's), `cx`, `cy`, `cz` (N, the contacts')"});
}

}  // namespace pbf

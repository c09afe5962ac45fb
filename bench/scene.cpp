#include "bench/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <stdexcept>

#include "engine/registry/style_registry.hpp"
#include "engine/sph/lattice.hpp"

namespace pbf::bench {

namespace {

constexpr double kG = 9.81;
constexpr double kEps = 1e-9;  // make_scene.py's EPS: floor() of an integer ratio stays that integer

// make_scene.py's default_dt: min(0.002, 0.4 h / v), v = sqrt(2 g L), rounded down to two
// significant digits.
double default_dt(double h, double L) {
  const double v = std::sqrt(2.0 * kG * L);
  const double dt = std::min(0.002, 0.4 * h / v);
  const double mag = std::pow(10.0, std::floor(std::log10(dt)) - 1);
  char text[32];
  std::snprintf(text, sizeof text, "%.2g", std::floor(dt / mag + kEps) * mag);
  return std::strtod(text, nullptr);
}

}  // namespace

DamBreakPlan plan_dam_break(std::size_t target) {
  // make_scene.py's scan and choose: s = a / k for k = 1, 2, ... until the count passes twice
  // the target; the count closest to the target wins, the coarser lattice on a tie.
  DamBreakPlan best;
  const double L = 1.0, a = L / 5;
  double best_miss = -1;
  for (int k = 1;; ++k) {
    const double s = a / k;
    const long ny = static_cast<long>(std::floor(L / s + kEps));
    const double count = static_cast<double>(k) * static_cast<double>(ny) * 2.0 * k;
    const double miss = std::abs(count - static_cast<double>(target));
    if (best_miss < 0 || miss < best_miss) {
      best_miss = miss;
      best.k = k;
      best.L = L;
      best.a = a;
      best.spacing = s;
      best.h = 2 * s;
      best.dt = default_dt(2 * s, L);
      best.particles = static_cast<std::size_t>(count);
    }
    if (count > 2.0 * static_cast<double>(target)) break;
  }
  return best;
}

DamBreak::DamBreak(std::size_t target) : plan_(plan_dam_break(target)), sim_(std::make_unique<Simulation>()) {
  Simulation& sim = *sim_;
  Domain domain;
  for (int c = 0; c < 3; ++c) domain.lo[c] = 0, domain.hi[c] = plan_.L;
  sim.set_domain(domain);
  sim.set_kernel_radius(plan_.h);
  sim.set_timestep(plan_.dt);
  sim.set_rest_density(1000);
  const double lo[3] = {0, 0, 0}, hi[3] = {plan_.a, plan_.L, 2 * plan_.a}, v[3] = {0, 0, 0};
  add_lattice(sim, lo, hi, plan_.spacing, v);
  if (sim.particles().size() != plan_.particles)
    throw std::runtime_error("dam break: the lattice holds " + std::to_string(sim.particles().size()) +
                             " particles, the plan " + std::to_string(plan_.particles));

  // scenarios/init_file.lua's PBF pipeline, which runs make_scene.py's files.
  const StyleRegistry& styles = StyleRegistry::builtin();
  sim.add_fix(styles.make_fix("gravity", "gravity", {{"acceleration", Vec3{0, 0, -kG}}}));
  sim.add_fix(styles.make_fix("pbf", "pbf", {{"iterations", std::int64_t{4}}}));
  sim.add_fix(styles.make_fix("vorticity", "vorticity", {}));
  sim.add_fix(styles.make_fix("xsph", "xsph", {}));
  sim.add_fix(styles.make_fix("walls", "box", {}));
  sim.run(kWarmupSteps);
  warm_time_ = sim.time();

  auto& P = sim.particles();
  const real* from[6] = {P.x(), P.y(), P.z(), P.vx(), P.vy(), P.vz()};
  for (int c = 0; c < 6; ++c) saved_[c].assign(from[c], from[c] + P.size());
  positions_dirty_ = true;  // so the first restore() builds lists at exactly these positions
  restore();
}

Fix& DamBreak::fix(const std::string& id) const {
  Fix* f = sim_->find_fix(id);
  if (!f) throw std::runtime_error("dam break: no fix '" + id + "'");
  return *f;
}

void DamBreak::restore() {
  auto& P = sim_->particles();
  if (positions_dirty_) {
    real* to[3] = {P.x(), P.y(), P.z()};
    for (int c = 0; c < 3; ++c) std::copy(saved_[c].begin(), saved_[c].end(), to[c]);
    sim_->positions_changed();
    sim_->refresh_neighbors();
    sim_->summed_density();
    positions_dirty_ = false;
  }
  if (velocities_dirty_) {
    real* to[3] = {P.vx(), P.vy(), P.vz()};
    for (int c = 0; c < 3; ++c) std::copy(saved_[3 + c].begin(), saved_[3 + c].end(), to[c]);
    velocities_dirty_ = false;
  }
}

namespace {

std::map<std::size_t, std::unique_ptr<DamBreak>>& scenes(bool stepping) {
  static std::map<std::size_t, std::unique_ptr<DamBreak>> passes, steps;
  return stepping ? steps : passes;
}

DamBreak& scene(std::size_t target, bool stepping) {
  auto& slot = scenes(stepping)[target];
  if (!slot) slot = std::make_unique<DamBreak>(target);
  return *slot;
}

}  // namespace

DamBreak& pass_scene(std::size_t target) { return scene(target, false); }
DamBreak& step_scene(std::size_t target) { return scene(target, true); }
DamBreak& rebuild_step_scene(std::size_t target) {
  scenes(true)[target].reset();
  return scene(target, true);
}

}  // namespace pbf::bench

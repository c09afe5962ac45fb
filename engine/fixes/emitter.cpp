// emitter: an inlet. Fluid enters through an opening, a rectangle or a disc with normal n
// (engine/fixes/emitter_opening.hpp: its N sites), at the velocity U, from `start` to `stop`.
// U is a speed along n or a vector, each a constant or a function of the time and the place,
// U(t, x) (a Lua function: engine/geometry/space_time_function.hpp).
//
// Particles have the lattice's mass m for the spacing s (the mass rule of pbf.lattice, so that
// the fluid enters at rest density); each stands for its rest volume V = m / rho0. Each site
// stands for an equal part A / N of the opening's area A, and the particles of a site follow
// one another at the distance L = N V / A (L is s within a few percent), so that site k's mass
// rate is m (U_k . n) / L = rho0 (A / N) (U_k . n), and the opening's
//   sum_k rho0 (A / N) (U_k . n) = rho0 A (U . n)            for a constant U,
//                                ~ rho0 integral (U . n) dA   for a profile
// (the midpoint rule over the sites' cells). Each site integrates its own advance at the start
// of each step (the exchange stage),
//   D_k += (U_k . n) dt,   U_k = U(t + dt/2, x_k),
// the midpoint rule in time (exact for a velocity linear in t); each time D_k reaches L a
// particle enters at site k with the velocity U_k, D_k - L ahead of the opening (where it
// would be had it entered on time), and D_k -= L. A U the same at every site keeps every D_k
// the same: the particles enter in layers of N. Per site, not at the opening's mean advance,
// so that with a profile the fluid enters at rest density at every site: layers at the mean
// advance would crowd a slow site's particles onto the last layer's.
//
// A function may give a zero normal speed (the inflow pauses there: the site lets nothing in,
// not even its first particle), not a negative one (the fluid would go back through the
// opening), nor a speed beyond 1e6 m/s or a value that is not finite: each stops the run,
// naming the parameter, the time and the place. The function is called at every open site
// at each step, in site order, in serial code (a Lua state belongs to one thread) and on every
// rank alike: every rank has the same D_k, and a function with state of its own sees the
// calls one process makes. It is not saved in a restart (the script gives it again); the D_k
// are.
//
// The particles due in a step that would land in fluid (fluid within s/2 of where one enters,
// along n, over its site's cell; for a layer: within s/2 of its plane over the opening) wait:
// their D_k stay at L until there is room, and the log says so once. Sites inside a solid are
// left out.
//
// An inlet zone (`buffer` > 0, for an opening under water or at a wall): the zone's particles
// move kinematically at their sites' U_k, and D_k is where site k's hindmost one stands, so a
// particle enters L behind it, never waiting (engine/fixes/inlet_zone.hpp).
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "engine/core/error.hpp"
#include "engine/core/parallel.hpp"
#include "engine/core/particle_flow.hpp"
#include "engine/core/simulation.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/fixes/emitter_opening.hpp"
#include "engine/fixes/inlet_zone.hpp"
#include "engine/geometry/solid_body.hpp"
#include "engine/geometry/space_time_function.hpp"
#include "engine/io/bytes.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/sph/mass.hpp"
#include "engine/sph/resolution.hpp"

namespace pbf {

namespace {

double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 scaled(const Vec3& a, double k) { return {a[0] * k, a[1] * k, a[2] * k}; }

class Emitter : public Fix {
 public:
  Emitter(const std::string& id, const Params& p)
      : Fix(id, "emitter"),
        opening_(p),
        start_(p.real("start")),
        stop_(p.real("stop")),
        spacing_(p.has("spacing") ? p.real("spacing") : 0),
        buffer_(p.real("buffer")) {
    if (p.has("speed") == p.has("velocity"))
      throw Error("give the inflow as 'speed' (along the normal) or as 'velocity' (a vector), one of the two");
    along_normal_ = p.has("speed");
    inflow_ = p.function(along_normal_ ? "speed" : "velocity");
    if (inflow_->constant()) {
      const Vec3 value = inflow_->at(0, opening_.center());
      velocity_ = along_normal_ ? scaled(opening_.normal(), value[0]) : value;
      if (!(dot(velocity_, opening_.normal()) > 0))
        throw Error(fmt::format("parameter 'velocity' ({}, {}, {}) points along the opening or back into it: its "
                                "part along the normal must be positive",
                                velocity_[0], velocity_[1], velocity_[2]));
    }
    if (!(stop_ > start_)) throw Error(fmt::format("parameter 'stop' ({} s) must come after 'start' ({} s)", stop_, start_));
  }

  std::vector<Stage> stages() const override {
    if (buffer_ > 0) return {Stage::exchange, Stage::external_forces, Stage::constraints, Stage::velocity_post};
    return {Stage::exchange};
  }
  // After the other fixes' velocity_post (vorticity, XSPH): the zone's velocity is the last word.
  Role role() const override { return Role::boundary; }
  bool runs_distributed() const override { return true; }  // each rank creates its share of a layer
  const ParticleFlow* particle_flow() const override { return &emitted_; }
  double created_mass(const Simulation& sim) const override {
    const double s = known_spacing(sim);
    return s > 0 ? lattice_mass(s, sim.kernels(), sim.rest_density()) : 0;
  }

  void init(Simulation& sim) override {
    const double s = spacing(sim);
    used_spacing_ = s;
    check_kernel_radius(sim.kernel_radius(), s, fmt::format("fix '{}' (emitter)", id()));
    mass_ = real(lattice_mass(s, sim.kernels(), sim.rest_density()));
    const Domain& d = sim.domain();
    const Vec3& c = opening_.center();
    if (!d.contains(real(c[0]), real(c[1]), real(c[2])))
      throw Error(fmt::format("parameter 'center' ({}, {}, {}) is outside the domain", c[0], c[1], c[2]));
    const Vec3 ahead = opening_.point({0, 0}, s);
    if (!d.contains(real(ahead[0]), real(ahead[1]), real(ahead[2]))) {
      const Vec3& n = opening_.normal();
      throw Error(fmt::format("parameters 'center' and 'normal': the opening at ({}, {}, {}) faces out of the domain "
                              "along ({:.3g}, {:.3g}, {:.3g}): the fluid would leave it as it enters",
                              c[0], c[1], c[2], n[0], n[1], n[2]));
    }
    opening_.lay_out(s);
    const std::size_t sites = opening_.sites();
    layer_distance_ = double(sites) * double(mass_) / sim.rest_density() / opening_.area();
    checked_ = false;
    if (started_ && distance_.size() != sites) {
      spdlog::warn("emitter '{}': its opening now has {} sites, {} before: every site starts a new layer", id(),
                   sites, distance_.size());
      started_ = false;
    }
    if (!started_) {
      distance_.assign(sites, layer_distance_);  // the first layer enters at `start`, in the opening's plane
      started_ = true;
    }
    // A distance the saved run left is below L (or L, waiting): a larger one (another L, a
    // damaged restart) enters once, not layer after layer.
    for (double& D : distance_) D = std::min(D, layer_distance_);
    site_velocity_.assign(sites, velocity_);
    site_velocity_real_.assign(sites, {real(velocity_[0]), real(velocity_[1]), real(velocity_[2])});
    due_.assign(sites, 0);
    due_sites_.reserve(sites);
    if (buffer_ > 0)
      zone_field_ = sim.particles().declare(
          {"inlet_" + id(), 1, "1 while the particle is in emitter " + id() + "'s inlet zone", true});
  }

  void exchange(Simulation& sim) override {
    const double t = sim.time(), dt = sim.timestep(), L = layer_distance_;
    if (!checked_) check_scene(sim);
    checked_ = true;
    active_ = t + 0.5 * dt >= start_ && t + 0.5 * dt < stop_;  // the steps whose middle is in [start, stop)
    if (!active_) return;
    if (!inflow_->constant()) evaluate(t + 0.5 * dt);
    const Vec3& n = opening_.normal();
    auto& P = sim.particles();
    const std::size_t before = P.size();
    if (buffer_ > 0) {  // D_k: where site k's hindmost zone particle stands
      zone_.find_back(P, opening_, 0.5 * used_spacing_, buffer_, zone_field_, !zone_filled_, L, distance_);
      zone_filled_ = true;
    } else {
      for (std::size_t k = 0; k < opening_.sites(); ++k)
        if (opening_.open(k)) distance_[k] += dot(site_velocity_[k], n) * dt;
    }
    for (;;) {
      bool any = false;
      for (std::size_t k = 0; k < opening_.sites(); ++k) {  // (a site whose inflow pauses admits nothing)
        due_[k] = opening_.open(k) && distance_[k] >= L && dot(site_velocity_[k], n) > 0;
        any = any || due_[k];
      }
      if (!any) break;
      if (buffer_ == 0 && blocked(sim, before)) {
        if (!said_blocked_)
          spdlog::warn("emitter '{}': fluid stands in front of the opening at t = {:.6g} s: it waits for room (said "
                       "once)",
                       id(), t);
        said_blocked_ = true;
        for (std::size_t k = 0; k < opening_.sites(); ++k)
          if (due_[k]) distance_[k] = L;
        break;
      }
      const std::size_t first = P.size();
      add_due(P);
      if (buffer_ > 0) std::fill(P.data(zone_field_) + first, P.data(zone_field_) + P.size(), real(1));
      for (std::size_t k = 0; k < opening_.sites(); ++k)
        if (due_[k]) distance_[k] -= L;
    }
    emitted_.count_from(P, before);
  }

  // The inlet zone: who is in it at the step's start (the indices hold from here to the step's
  // end), and where they are by its end.
  void external_forces(Simulation& sim) override {
    if (active_) zone_.take(sim.particles(), opening_, 0.5 * used_spacing_, buffer_, zone_field_);
    else zone_.clear();  // a closed inlet moves nothing
  }
  void constraint(Simulation& sim, int) override {
    zone_.move(sim.particles(), site_velocity_real_, sim.timestep(), false);
  }
  void velocity_post(Simulation& sim) override {
    zone_.move(sim.particles(), site_velocity_real_, sim.timestep(), true);
  }

  void save_state(ByteWriter& w) const override {
    w.put(static_cast<std::uint64_t>(distance_.size()));
    w.put_array(distance_.data(), distance_.size());
    w.put(static_cast<std::uint8_t>(started_));
    w.put(static_cast<std::uint8_t>(said_blocked_));
    w.put(static_cast<std::uint8_t>(zone_filled_));
    emitted_.save(w);
  }
  void restore_state(ByteReader& r) override {
    r.get_array(distance_, r.get<std::uint64_t>());
    for (double D : distance_)
      if (!(D >= 0 && D <= 1e300))
        throw Error(fmt::format("{}: fix '{}' (emitter): a site's distance is {}", r.what(), id(), D));
    started_ = r.get<std::uint8_t>() != 0;
    said_blocked_ = r.get<std::uint8_t>() != 0;
    zone_filled_ = r.get<std::uint8_t>() != 0;
    emitted_.restore(r);
  }

 private:
  // The spacing given, else the scene's (from its particles' mass, or as this emitter last
  // found it); 0 when there is none of these.
  double known_spacing(const Simulation& sim) const {
    if (spacing_ > 0) return spacing_;
    if (sim.global_count() > 0) return lattice_spacing(sim.particle_mass(), sim.kernels(), sim.rest_density());
    return used_spacing_;
  }
  double spacing(const Simulation& sim) const {
    const double s = known_spacing(sim);
    if (s == 0)
      throw Error(fmt::format("fix '{}' (emitter): parameter 'spacing' is needed: the scene has no particles to take "
                              "it from",
                              id()));
    return s;
  }

  // Once a run's solids have their maps: sites inside a solid are left out (all of them: an
  // error), and a sink over the opening would take the fluid as it enters.
  void check_scene(const Simulation& sim) {
    std::vector<char> closed(opening_.sites(), 0);
    for (std::size_t k = 0; k < opening_.sites(); ++k)
      for (const SolidBody* body : sim.solid_bodies()) {
        const auto depth = body->depth_in_wall(opening_.point(k, 0));
        if (depth && *depth > 0) closed[k] = 1;
      }
    if (std::find(closed.begin(), closed.end(), 0) == closed.end())
      throw Error(fmt::format("fix '{}' (emitter): the opening lies inside a solid: no fluid can enter", id()));
    opening_.close(closed);
    const Vec3 ahead = opening_.point({0, 0}, 0.5 * used_spacing_);
    const real q[3] = {real(ahead[0]), real(ahead[1]), real(ahead[2])};
    for (const auto& f : sim.fixes())
      if (f.get() != this && f->removes_at(q))
        throw Error(fmt::format("fix '{}' (emitter): fix '{}' ({}) removes the fluid at the opening as it enters",
                                id(), f->id(), f->style()));
  }

  // U_k at time t at every open site, in site order.
  void evaluate(double t) {
    for (std::size_t k = 0; k < opening_.sites(); ++k) {
      if (!opening_.open(k)) continue;
      const Vec3 U = inflow_at(t, opening_.point(k, 0));
      site_velocity_[k] = U;
      site_velocity_real_[k] = {real(U[0]), real(U[1]), real(U[2])};
    }
  }

  // The function's U at time t at the point x, checked.
  Vec3 inflow_at(double t, const Vec3& x) const {
    const char* name = along_normal_ ? "speed" : "velocity";
    Vec3 value;
    try {
      value = inflow_->at(t, x);
    } catch (const Error& e) {
      // The run loop names the step and the fix of a message that does not say where; one
      // that names the script's line passes as it is, so it names the fix here.
      if (e.located()) throw Error(fmt::format("fix '{}' (emitter): parameter '{}': {}", id(), name, e.what()), true);
      throw Error(fmt::format("parameter '{}': {}", name, e.what()));
    }
    const Vec3 U = along_normal_ ? scaled(opening_.normal(), value[0]) : value;
    const double normal = dot(U, opening_.normal());
    const bool finite = std::isfinite(value[0]) && std::isfinite(U[0]) && std::isfinite(U[1]) && std::isfinite(U[2]);
    if (finite && std::sqrt(dot(U, U)) <= 1e6 && normal >= 0) return U;
    // What is wrong, said only now: this is called at every site at every step.
    const std::string what = along_normal_ ? "a speed" : "a velocity";
    std::string wrong;
    if (!finite) wrong = what + " must be finite";
    else if (normal >= 0) wrong = what + " must be at most 1e6 m/s";
    else if (along_normal_) wrong = "a speed must be >= 0 (0 pauses the inflow)";
    else wrong = fmt::format("its part along the normal, {} m/s, must be >= 0 (0 pauses the inflow)", normal);
    auto number = [](double v) { return std::isnan(v) ? std::string("nan") : fmt::format("{}", v); };
    const std::string gave =
        along_normal_ ? number(value[0]) + " m/s"
                      : fmt::format("{{{}, {}, {}}}", number(value[0]), number(value[1]), number(value[2]));
    throw Error(fmt::format("parameter '{}': {} at t = {} s, (x, y, z) = ({:.6g}, {:.6g}, {:.6g}) gave {}: {}", name,
                            inflow_->description(), t, x[0], x[1], x[2], gave, wrong));
  }

  // Whether any particle (of the `count` there before this step's) lies within s/2 of where a
  // due site's particle enters, along n, and over that site's cell (at the opening's edge, up
  // to s/2 beyond it): on every rank's.
  bool blocked(const Simulation& sim, std::size_t count) const {
    const auto& P = sim.particles();
    const double s = used_spacing_, L = layer_distance_;
    std::int64_t found = 0;
#pragma omp parallel for schedule(static) reduction(+ : found)
    for (std::size_t i = 0; i < count; ++i) {
      const auto o = opening_.offset({double(P.x()[i]), double(P.y()[i]), double(P.z()[i])});
      if (!opening_.over(o[0], o[1], 0.5 * s)) continue;
      const std::size_t k = opening_.nearest_site(o[0], o[1]);
      found += due_[k] && std::fabs(o[2] - (distance_[k] - L)) < 0.5 * s;
    }
    return (P.distributed() ? comm::sum(found) : found) > 0;
  }

  // The due sites' particles, each D_k - L in front of the opening: each rank its share,
  // numbered as one process numbers them.
  void add_due(Particles& P) {
    due_sites_.clear();  // (kept from step to step: a step allocates nothing)
    for (std::size_t k = 0; k < opening_.sites(); ++k)
      if (due_[k]) due_sites_.push_back(k);
    const std::size_t first = P.size();
    const Particles::Share share = P.share(due_sites_.size());
    for (std::size_t j = share.first; j < share.end; ++j) {
      const std::size_t k = due_sites_[j];
      const Vec3 q = opening_.point(k, distance_[k] - layer_distance_);
      const real x[3] = {real(q[0]), real(q[1]), real(q[2])};
      P.add(x, site_velocity_real_[k].data(), mass_);
    }
    P.finish_source(first);
  }

  Opening opening_;
  bool along_normal_ = false;  // `speed` given: U = speed n
  SpaceTimeFunctionPtr inflow_;
  Vec3 velocity_{};             // a constant U (else 0 until evaluated)
  double start_, stop_, spacing_;
  double buffer_;               // the inlet zone's depth (0: none)
  double layer_distance_ = 0;  // L: a site's particle enters each time the fluid there advances this far
  double used_spacing_ = 0;    // the spacing of the last run
  real mass_ = 0;
  std::vector<Vec3> site_velocity_;                    // U_k of this step
  std::vector<std::array<real, 3>> site_velocity_real_;  // the same, as the particles hold it
  std::vector<char> due_;                              // the sites whose particle enters in this round
  std::vector<std::size_t> due_sites_;                 // the same, listed
  InletZone zone_;
  FieldId zone_field_ = 0;         // "inlet_<id>": 1 for the zone's particles
  // State: the distance advanced at each site since its last particle, and what has entered.
  std::vector<double> distance_;
  bool started_ = false, said_blocked_ = false, checked_ = false, active_ = false;
  bool zone_filled_ = false;  // the fluid in the zone at the inlet's first step joined it
  ParticleFlow emitted_;
};

}  // namespace

void register_emitter(StyleRegistry& r) {
  r.add({"emitter",
         StyleKind::fix,
         "an inlet: fluid enters through a rectangle or a disc, in layers at the particle spacing, at a set velocity",
         {ParamSpec{"shape", ParamType::String, std::string("rectangle"), "", "the opening: \"rectangle\" or \"disc\""}
              .one_of({"rectangle", "disc"}),
          ParamSpec{"center", ParamType::Vector3, std::nullopt, "m", "the opening's centre"}.magnitude_at_most(1e6),
          ParamSpec{"normal", ParamType::Vector3, std::nullopt, "", "the direction the fluid enters along (any length)"}
              .magnitude_at_most(1e6),
          ParamSpec{"size", ParamType::Vector2, std::nullopt, "m",
                    "rectangle: its sides {a, b}, a along 'axis', each rounded to a whole number of spacings", true}
              .above_within(0, 1e6),
          ParamSpec{"radius", ParamType::Real, std::nullopt, "m", "disc: its radius", true}.above_within(0, 1e6),
          ParamSpec{"axis", ParamType::Vector3, std::nullopt, "",
                    "rectangle: the direction of its first side (default: the coordinate axis the normal leans on "
                    "least, made normal to it)",
                    true}
              .magnitude_at_most(1e6),
          ParamSpec{"speed", ParamType::RealFunction, std::nullopt, "m/s",
                    "the inflow speed along the normal, or function(t, x, y, z) giving it at time t at a site (x, y, "
                    "z) of the opening (>= 0: 0 pauses the inflow)",
                    true}
              .above_within(0, 1e6),
          ParamSpec{"velocity", ParamType::Vector3Function, std::nullopt, "m/s",
                    "the inflow velocity, instead of 'speed' (its part along the normal positive), or function(t, x, "
                    "y, z) giving {ux, uy, uz} at time t at a site (x, y, z) (that part >= 0)",
                    true}
              .magnitude_at_most(1e6),
          ParamSpec{"buffer", ParamType::Real, 0.0, "m",
                    "an inlet zone this deep ahead of the opening: its particles move kinematically at the set "
                    "velocity (that of the site they are over) and new ones enter behind them without waiting (for an "
                    "opening under water or at a wall; 0: none)"}
              .within(0, 1e6),
          ParamSpec{"start", ParamType::Real, 0.0, "s", "when the fluid starts to enter"}.magnitude_at_most(1e12),
          ParamSpec{"stop", ParamType::Real, 1e12, "s", "when it stops"}.magnitude_at_most(1e12),
          ParamSpec{"spacing", ParamType::Real, std::nullopt, "m",
                    "the particle spacing (default: the scene's, from its particles' mass; needed when the scene "
                    "starts empty)",
                    true}
              .above_within(0, 1e6)},
         [](const std::string& id, const Params& p) { return std::make_unique<Emitter>(id, p); }, nullptr});
}

}  // namespace pbf

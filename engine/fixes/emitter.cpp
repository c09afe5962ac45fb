// emitter: an inlet. Fluid enters through an opening, a rectangle (sides a along u, b along
// v) or a disc (radius r) centred at c in the plane normal to n, at the velocity U (a speed
// along n, or a vector whose part along n is positive), from `start` to `stop`.
//
// Particles come in layers, each particle with the lattice's mass m for the spacing s (the
// mass rule of pbf.lattice, so that the fluid enters at rest density); each stands for its
// rest volume V = m / rho0. A layer holds N sites in the opening's plane: for a rectangle
// na x nb of them, na = round(a/s) and nb = round(b/s), at the centres of na x nb equal cells
// of the opening; for a disc the N = round(pi r^2 / s^2) sites of the square lattice of
// spacing s nearest its centre. Layers follow one another at the distance L = N V / A (A the
// opening's area, a b or pi r^2; L is s within a few percent), so that the mass rate is
//   N m (U . n) / L = rho0 A (U . n),
// the set one. The distance the fluid has advanced since the last layer is integrated step by
// step at the start of each step (the exchange stage), D += (U . n) dt, and each time it
// reaches L a layer enters, D - L ahead of the opening (where it would be had it entered on
// time), and D -= L.
//
// A layer that would land in fluid (fluid within s/2 of its plane over the opening) waits: D
// stays at L until there is room, and the log says so once. Sites inside a solid are left out.
//
// An inlet zone (`buffer` > 0, for an opening under water or against a wall, where the fluid
// ahead would block it): after each step's velocity update the particles over the opening
// within `buffer` ahead of it (and s/2 behind) move at U exactly, so that the zone feeds the
// fluid ahead at the set rate and no fluid flows back over the opening (DualSPHysics's inlet
// buffer, simplified: the zone's particles are fluid, their velocity imposed).
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "engine/core/error.hpp"
#include "engine/core/parallel.hpp"
#include "engine/core/particle_flow.hpp"
#include "engine/core/simulation.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/geometry/solid_body.hpp"
#include "engine/io/bytes.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/sph/mass.hpp"
#include "engine/sph/resolution.hpp"

namespace pbf {

namespace {

double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 scaled(const Vec3& a, double k) { return {a[0] * k, a[1] * k, a[2] * k}; }
Vec3 unit(const Vec3& a) { return scaled(a, 1 / std::sqrt(dot(a, a))); }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

class Emitter : public Fix {
 public:
  Emitter(const std::string& id, const Params& p)
      : Fix(id, "emitter"),
        disc_(p.string("shape") == "disc"),
        center_(p.vec3("center")),
        start_(p.real("start")),
        stop_(p.real("stop")),
        spacing_(p.has("spacing") ? p.real("spacing") : 0),
        buffer_(p.real("buffer")) {
    const Vec3 normal = p.vec3("normal");
    if (!(dot(normal, normal) > 0)) throw Error("parameter 'normal' is the zero vector: the opening needs a direction");
    n_ = unit(normal);
    if (p.has("speed") == p.has("velocity"))
      throw Error("give the inflow as 'speed' (along the normal) or as 'velocity' (a vector), one of the two");
    velocity_ = p.has("speed") ? scaled(n_, p.real("speed")) : p.vec3("velocity");
    speed_ = dot(velocity_, n_);
    if (!(speed_ > 0))
      throw Error(fmt::format("parameter 'velocity' ({}, {}, {}) points along the opening or back into it: its part "
                              "along the normal must be positive",
                              velocity_[0], velocity_[1], velocity_[2]));
    if (!(stop_ > start_)) throw Error(fmt::format("parameter 'stop' ({} s) must come after 'start' ({} s)", stop_, start_));
    if (disc_ != p.has("radius") || disc_ == p.has("size"))
      throw Error(disc_ ? "a disc opening takes 'radius' (not 'size')" : "a rectangle opening takes 'size' {a, b} (not 'radius')");
    if (disc_) {
      radius_ = p.real("radius");
    } else {
      size_ = p.vec2("size");
    }
    // The opening's axes: u along `axis` (or the coordinate axis the normal leans on least), v = n x u.
    Vec3 axis = p.has("axis") ? p.vec3("axis") : Vec3{0, 0, 0};
    if (!p.has("axis")) {
      int least = 0;
      for (int a = 1; a < 3; ++a)
        if (std::fabs(n_[a]) < std::fabs(n_[least])) least = a;
      axis[least] = 1;
    }
    const Vec3 along = {axis[0] - dot(axis, n_) * n_[0], axis[1] - dot(axis, n_) * n_[1], axis[2] - dot(axis, n_) * n_[2]};
    if (!(dot(along, along) > 1e-12 * dot(axis, axis)))
      throw Error("parameter 'axis' is along the normal: it must give a direction in the opening's plane");
    u_ = unit(along);
    v_ = cross(n_, u_);
  }

  std::vector<Stage> stages() const override {
    if (buffer_ > 0) return {Stage::exchange, Stage::velocity_post};
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
    if (!d.contains(real(center_[0]), real(center_[1]), real(center_[2])))
      throw Error(fmt::format("parameter 'center' ({}, {}, {}) is outside the domain", center_[0], center_[1], center_[2]));
    const Vec3 ahead = {center_[0] + s * n_[0], center_[1] + s * n_[1], center_[2] + s * n_[2]};
    if (!d.contains(real(ahead[0]), real(ahead[1]), real(ahead[2])))
      throw Error(fmt::format("parameters 'center' and 'normal': the opening at ({}, {}, {}) faces out of the domain "
                              "along ({:.3g}, {:.3g}, {:.3g}): the fluid would leave it as it enters",
                              center_[0], center_[1], center_[2], n_[0], n_[1], n_[2]));
    lay_out_sites(s);
    const double area = disc_ ? M_PI * radius_ * radius_ : size_[0] * size_[1];
    layer_distance_ = double(sites_.size()) * double(mass_) / sim.rest_density() / area;
    checked_ = false;
    if (!started_) {
      distance_ = layer_distance_;  // the first layer enters at `start`, in the opening's plane
      started_ = true;
    }
  }

  void exchange(Simulation& sim) override {
    const double t = sim.time(), dt = sim.timestep(), s = used_spacing_, L = layer_distance_;
    if (!checked_) check_scene(sim);
    checked_ = true;
    if (t + 0.5 * dt < start_ || t + 0.5 * dt >= stop_) return;  // the steps whose middle is within [start, stop)
    distance_ += speed_ * dt;
    auto& P = sim.particles();
    const std::size_t before = P.size();
    while (distance_ >= L) {
      const double ahead = distance_ - L;
      if (blocked(sim, before, ahead, s)) {
        if (!said_blocked_)
          spdlog::warn("emitter '{}': fluid stands in front of the opening at t = {:.6g} s: it waits for room (said "
                       "once)",
                       id(), t);
        said_blocked_ = true;
        distance_ = L;
        break;
      }
      add_layer(P, ahead);
      distance_ -= L;
    }
    emitted_.count_from(P, before);
  }

  // The inlet zone moves at the set velocity.
  void velocity_post(Simulation& sim) override {
    auto& P = sim.particles();
    const double s = used_spacing_;
    const real v[3] = {real(velocity_[0]), real(velocity_[1]), real(velocity_[2])};
    real *vx = P.vx(), *vy = P.vy(), *vz = P.vz();
    const real *x = P.x(), *y = P.y(), *z = P.z();
    for_particles(P.size(), [&](std::size_t i) {
      const Vec3 d = {double(x[i]) - center_[0], double(y[i]) - center_[1], double(z[i]) - center_[2]};
      const double along = dot(d, n_);
      if (along < -0.5 * s || along >= buffer_ || !over_opening(dot(d, u_), dot(d, v_), 0)) return;
      vx[i] = v[0];
      vy[i] = v[1];
      vz[i] = v[2];
    });
  }

  void save_state(ByteWriter& w) const override {
    w.put(distance_);
    w.put(static_cast<std::uint8_t>(started_));
    w.put(static_cast<std::uint8_t>(said_blocked_));
    emitted_.save(w);
  }
  void restore_state(ByteReader& r) override {
    distance_ = r.get<double>();
    started_ = r.get<std::uint8_t>() != 0;
    said_blocked_ = r.get<std::uint8_t>() != 0;
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

  // The opening's sites, as offsets (along u, along v) from the centre.
  void lay_out_sites(double s) {
    if (disc_ ? 2 * radius_ < s : (size_[0] < s || size_[1] < s))
      throw Error(fmt::format("parameter '{}': the opening is narrower than one particle spacing ({} m)",
                              disc_ ? "radius" : "size", s));
    sites_.clear();
    if (disc_) {  // the lattice sites nearest the centre, nearer first, then by row and column
      const long half = static_cast<long>(std::ceil(radius_ / s)) + 1;
      std::vector<std::array<double, 3>> candidates;  // (squared distance, a, b)
      for (long j = -half; j <= half; ++j)
        for (long i = -half; i <= half; ++i) {
          const double a = double(i) * s, b = double(j) * s;
          candidates.push_back({a * a + b * b, a, b});
        }
      std::stable_sort(candidates.begin(), candidates.end(), [](const auto& x, const auto& y) { return x[0] < y[0]; });
      const auto count = static_cast<std::size_t>(std::max(1.0, std::round(M_PI * radius_ * radius_ / (s * s))));
      for (std::size_t k = 0; k < count; ++k) sites_.push_back({candidates[k][1], candidates[k][2]});
    } else {
      const long na = std::lround(size_[0] / s), nb = std::lround(size_[1] / s);
      const double da = size_[0] / double(na), db = size_[1] / double(nb);
      for (long j = 0; j < nb; ++j)
        for (long i = 0; i < na; ++i)
          sites_.push_back({(double(i) + 0.5 - 0.5 * double(na)) * da, (double(j) + 0.5 - 0.5 * double(nb)) * db});
    }
  }

  // Once a run's solids have their maps: sites inside a solid are left out (all of them: an
  // error), and a sink over the opening would take the fluid as it enters.
  void check_scene(const Simulation& sim) {
    std::vector<std::array<double, 2>> open;
    for (const auto& site : sites_) {
      const Vec3 q = at(site, 0);
      bool inside = false;
      for (const SolidBody* body : sim.solid_bodies()) {
        const auto depth = body->depth_in_wall(q);
        inside = inside || (depth && *depth > 0);
      }
      if (!inside) open.push_back(site);
    }
    if (open.empty())
      throw Error(fmt::format("fix '{}' (emitter): the opening lies inside a solid: no fluid can enter", id()));
    sites_ = open;
    const double s = used_spacing_;
    const Vec3 ahead = at({0, 0}, 0.5 * s);
    const real q[3] = {real(ahead[0]), real(ahead[1]), real(ahead[2])};
    for (const auto& f : sim.fixes())
      if (f.get() != this && f->removes_at(q))
        throw Error(fmt::format("fix '{}' (emitter): fix '{}' ({}) removes the fluid at the opening as it enters",
                                id(), f->id(), f->style()));
  }

  Vec3 at(const std::array<double, 2>& site, double ahead) const {
    Vec3 q;
    for (int a = 0; a < 3; ++a) q[a] = center_[a] + site[0] * u_[a] + site[1] * v_[a] + ahead * n_[a];
    return q;
  }

  // Whether any particle (of the `count` there before this step's layers) lies within s/2 of
  // the layer's plane and within s/2 of the opening: on every rank's.
  bool blocked(const Simulation& sim, std::size_t count, double ahead, double s) const {
    const auto& P = sim.particles();
    std::int64_t found = 0;
#pragma omp parallel for schedule(static) reduction(+ : found)
    for (std::size_t i = 0; i < count; ++i) {
      const Vec3 d = {double(P.x()[i]) - center_[0], double(P.y()[i]) - center_[1], double(P.z()[i]) - center_[2]};
      if (std::fabs(dot(d, n_) - ahead) >= 0.5 * s) continue;
      found += over_opening(dot(d, u_), dot(d, v_), 0.5 * s);
    }
    return (P.distributed() ? comm::sum(found) : found) > 0;
  }

  // Whether in-plane offsets (a, b) from the centre lie over the opening, widened by `margin`.
  bool over_opening(double a, double b, double margin) const {
    if (disc_) return a * a + b * b < (radius_ + margin) * (radius_ + margin);
    return std::fabs(a) < 0.5 * size_[0] + margin && std::fabs(b) < 0.5 * size_[1] + margin;
  }

  // One layer, `ahead` in front of the opening: each rank its share of the sites, numbered as
  // one process numbers them.
  void add_layer(Particles& P, double ahead) {
    const std::size_t first = P.size();
    const Particles::Share share = P.share(sites_.size());
    const real v[3] = {real(velocity_[0]), real(velocity_[1]), real(velocity_[2])};
    for (std::size_t k = share.first; k < share.end; ++k) {
      const Vec3 q = at(sites_[k], ahead);
      const real x[3] = {real(q[0]), real(q[1]), real(q[2])};
      P.add(x, v, mass_);
    }
    P.finish_source(first);
  }

  bool disc_;
  Vec3 center_, n_{}, u_{}, v_{}, velocity_{};
  Vec2 size_{0, 0};
  double radius_ = 0, speed_ = 0, start_, stop_, spacing_;
  double buffer_;               // the inlet zone's depth (0: none)
  double layer_distance_ = 0;  // L: a layer enters each time the fluid advances this far
  double used_spacing_ = 0;    // the spacing of the last run
  real mass_ = 0;
  std::vector<std::array<double, 2>> sites_;
  // State: the distance advanced since the last layer, and what has entered.
  double distance_ = 0;
  bool started_ = false, said_blocked_ = false, checked_ = false;
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
          ParamSpec{"speed", ParamType::Real, std::nullopt, "m/s", "the inflow speed along the normal", true}
              .above_within(0, 1e6),
          ParamSpec{"velocity", ParamType::Vector3, std::nullopt, "m/s",
                    "the inflow velocity, instead of 'speed' (its part along the normal must be positive)", true}
              .magnitude_at_most(1e6),
          ParamSpec{"buffer", ParamType::Real, 0.0, "m",
                    "an inlet zone this deep ahead of the opening, whose particles move at the set velocity (for an "
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

// wcsph: the pressure of weakly compressible SPH (Monaghan 1994; Becker & Teschner 2007),
// in the forces stage after the neighbour search:
//   density     summation: rho_i = sum_j m_j W(x_ij) + walls (the density every style
//               and compute of the engine uses, and the one the mass rule sets to rho0), or
//               continuity: rho_i += dt sum_j m_j (v_i - v_j) . gradW_ij  [+ dt D_i]
//               + dt 2 (v_i - v_wall) . grad(rho_wall)  (a moving wall at its own velocity)
//   diffusion   (continuity only; delta-SPH, Molteni & Colagrossi 2009, with the hydrostatic
//               part left out as Fourtakas et al. 2019 do, so that a column at rest keeps its
//               density profile):
//               D_i = 2 delta h_s c0 sum_j V_j ((rho_j - rho_i) - rho0 g (z_i - z_j) / c0^2) (-F_ij)
//               with gradW_ij = F_ij x_ij, V_j = m_j / rho_j and h_s = h / 2 the smoothing
//               length (h the kernel's radius). It damps the density noise, and the acoustic
//               ringing after an impact, that the continuity equation otherwise keeps.
//   pressure    tait:   p = B ((rho/rho0)^gamma - 1),  B = rho0 c0^2 / gamma
//               linear: p = c0^2 (rho - rho0)
//               negative pressures (a stretched free surface) clamped to 0 unless kept
//   force       a_i += -sum_j m_j (p_i/rho_i^2 + p_j/rho_j^2) gradW_ij   (Wendland C2)
//               a_i += -2 p_i/rho_i^2 grad(rho_wall)_i                  (walls as mirrored fluid)
// The accelerations go to the integrator's "acceleration" field (leapfrog). Two stops, each
// before garbage: a step longer than h / c0, beyond which the leapfrog's sound waves grow (the
// largest stable step measured on the dam break is 1.0 h / c0: docs/physics.md, "The largest
// stable step"), and a density more than max_density_error above rho0 (a step too large for
// the speeds, or a start too compressed).
#include <cmath>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "engine/core/error.hpp"
#include "engine/core/parallel.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/io/bytes.hpp"
#include "engine/core/simulation.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/sph/compression_watch.hpp"
#include "engine/sph/mass.hpp"

namespace pbf {

namespace {

// The default sound speed, 10 sqrt(2 g H), H the fluid's height when first measured (the z
// extent of the particles plus one spacing): flow speeds stay below about sqrt(2 g H), so
// the Mach number stays under 0.1 and the density varies by about 1% (Monaghan 1994).
double default_sound_speed(const Simulation& sim, double gravity) {
  const auto& P = sim.particles();
  if (sim.global_count() == 0)
    throw Error("parameter 'sound_speed': the default, 10 sqrt(2 g H), measures the fluid's height H, and there is "
                "no fluid yet: give the sound speed");
  double lo = INFINITY, hi = -INFINITY;
  for (std::size_t i = 0; i < P.size(); ++i) lo = std::min(lo, double(P.z()[i])), hi = std::max(hi, double(P.z()[i]));
  if (P.distributed()) lo = comm::min(lo), hi = comm::max(hi);  // every rank's
  const double height = hi - lo + lattice_spacing(sim.particle_mass(), sim.kernels(), sim.rest_density());
  return 10 * std::sqrt(2 * std::fabs(gravity) * height);
}

class Wcsph : public Fix {
 public:
  Wcsph(const std::string& id, const Params& p)
      : Fix(id, "wcsph"),
        eos_(p.string("eos")),
        density_(p.string("density")),
        gamma_(p.real("gamma")),
        c0_(p.real("sound_speed")),
        gravity_(p.real("gravity")),
        diffusion_(p.real("diffusion")),
        keep_negative_(p.boolean("negative_pressure")),
        max_error_(p.real("max_density_error")) {
    if (diffusion_ > 0 && density_ != "continuity")
      throw Error("parameter 'diffusion' needs density = \"continuity\": the summed density has no noise to diffuse");
  }

  std::vector<Stage> stages() const override { return {Stage::forces}; }
  Role role() const override { return Role::solver; }
  bool needs_neighbors() const override { return true; }
  bool adds_accelerations() const override { return true; }
  std::vector<const char*> exclusive_jobs() const override { return {"pressure solver"}; }

  void init(Simulation& sim) override {
    auto& P = sim.particles();
    const bool continuity = density_ == "continuity";
    const bool fresh = !P.find("density");
    rho_ = P.declare({"density", 1, "SPH density (kg/m^3)", continuity});
    pressure_ = P.declare({"pressure", 1, "pressure from the equation of state (Pa)", false});
    accel_ = P.declare(kAccelerationField);
    if (c0_ == 0) c0_ = default_sound_speed(sim, gravity_);  // once: a restart keeps it
    if (c0_ == 0)
      throw Error("parameter 'gravity' is 0, so the default sound speed 10 sqrt(2 g H) is 0: give 'sound_speed'");
    // A new field holds, before the first step, the density the solver starts from (below).
    filled_ = fresh;
    if (fresh) start_density(sim, {}, true);
    // The pressure of the density the run starts from: the field is recomputed before each
    // step reads it, but probes and dumps at the start of a run read it as it is.
    pressure_from_density(sim, P.data(rho_), P.data(pressure_));
  }

  // Particles added between runs start as a new field does (an integrated density of 0 would
  // be a vacuum, the pressure force pulling them apart: NaN within a step).
  void init_new_particles(Simulation& sim, std::span<const std::uint32_t> fresh) override {
    // Within a run (an emitter's) the integrated density starts at rest density; the summed
    // density and the pressure are computed before they are read.
    if (sim.running()) {
      if (density_ == "continuity") start_density(sim, fresh, false);
      return;
    }
    if (filled_) return;  // init just set every particle's
    start_density(sim, fresh, false);
    auto& P = sim.particles();
    pressure_from_density(sim, P.data(rho_), P.data(pressure_));
  }

  double signal_speed() const override { return c0_; }
  bool runs_distributed() const override { return true; }  // ghosts' density and pressure refreshed

  void forces(Simulation& sim) override {
    // The summed density first: were the lists stale it would rebuild them, and the ghosts
    // with them, which moves the arrays under any pointer taken before.
    if (density_ == "summation") sim.summed_density();
    auto& P = sim.particles();
    const auto& grid = sim.neighbors();
    const Kernels& K = sim.kernels();
    const std::size_t n = P.size();
    const real *x = P.x(), *y = P.y(), *z = P.z(), *m = P.mass(), *vx = P.vx(), *vy = P.vy(), *vz = P.vz();
    real *rho = P.data(rho_), *p = P.data(pressure_);
    real *ax = P.data(accel_, 0), *ay = P.data(accel_, 1), *az = P.data(accel_, 2);
    const real dt = real(sim.timestep());
    check_timestep(sim);

    const auto& walls = sim.density_boundaries();
    if (density_ == "summation") {
      const auto& summed = sim.summed_density();
      std::copy(summed.begin(), summed.end(), rho);
    } else {
      drho_.resize(n);
      const real diffusion = real(diffusion_ * sim.kernel_radius() * c0_);  // 2 delta h_s c0, h_s = h / 2
      const real hydrostatic = real(sim.rest_density() * std::fabs(gravity_) / (c0_ * c0_));
      for_particles(n, [&](std::size_t i) {
        real sum = 0, diffused = 0;
        grid.for_each_neighbor(i, x, y, z, [&](std::uint32_t j, real dx, real dy, real dz, real r2) {
          const real g = K.grad_factor(r2);
          sum += m[j] * g * ((vx[i] - vx[j]) * dx + (vy[i] - vy[j]) * dy + (vz[i] - vz[j]) * dz);
          diffused -= m[j] / rho[j] * ((rho[j] - rho[i]) - hydrostatic * dz) * g;
        });
        sum += diffusion * diffused;
        // Walls as mirrored fluid: the mirror image moves with the normal velocity reversed,
        // so approaching a wall raises the density by 2 (v - v_wall) . grad(rho_wall).
        real wall_rho = 0, grad[3] = {0, 0, 0}, moving = 0;
        for (const DensityBoundary* w : walls) {
          const real before[3] = {grad[0], grad[1], grad[2]};
          w->add_density(sim, x[i], y[i], z[i], i, wall_rho, grad);
          const real own[3] = {grad[0] - before[0], grad[1] - before[1], grad[2] - before[2]};
          const real q[3] = {x[i], y[i], z[i]};
          real vw[3];
          if ((own[0] != 0 || own[1] != 0 || own[2] != 0) && w->wall_velocity(sim, q, vw))
            moving += vw[0] * own[0] + vw[1] * own[1] + vw[2] * own[2];
        }
        drho_[i] = sum + 2 * (vx[i] * grad[0] + vy[i] * grad[1] + vz[i] * grad[2]) - 2 * moving;
      });
      for_particles(n, [&](std::size_t i) { rho[i] += dt * drho_[i]; });
    }
    check_density(sim, rho);
    if (sim.step() % kWatchEvery == 0) watch_compression(sim, rho);

    pressure_from_density(sim, rho, p);
    sim.update_ghosts({rho, p});  // the force reads them at neighbours

    for_particles(n, [&](std::size_t i) {
      const real pi = p[i] / (rho[i] * rho[i]);
      real a[3] = {0, 0, 0};
      grid.for_each_neighbor(i, x, y, z, [&](std::uint32_t j, real dx, real dy, real dz, real r2) {
        const real s = -m[j] * (pi + p[j] / (rho[j] * rho[j])) * K.grad_factor(r2);
        a[0] += s * dx;
        a[1] += s * dy;
        a[2] += s * dz;
      });
      if (pi != 0)  // each wall as fluid mirrored at the same pressure; it takes the opposite push
        for (DensityBoundary* w : walls) {
          real wall_rho = 0, grad[3] = {0, 0, 0}, push[3];
          w->add_density(sim, x[i], y[i], z[i], i, wall_rho, grad);
          for (int c = 0; c < 3; ++c) {
            a[c] -= 2 * pi * grad[c];
            push[c] = -2 * pi * grad[c] * m[i] * dt;
          }
          w->record_push(i, push);
        }
      ax[i] += a[0];
      ay[i] += a[1];
      az[i] += a[2];
    });
  }

  void save_state(ByteWriter& w) const override { w.put(c0_); }
  void restore_state(ByteReader& r) override { c0_ = r.get<double>(); }

 private:
  // The mean compression, every kWatchEvery steps (a pass and, on several ranks, a reduction).
  static constexpr std::int64_t kWatchEvery = 10;
  void watch_compression(const Simulation& sim, const real* rho) {
    const auto& P = sim.particles();
    const double inv_rho0 = 1 / sim.rest_density();
    const double compressed = deterministic_sum(
        P.size(), [&](std::size_t i) { return std::max(0.0, double(rho[i]) * inv_rho0 - 1); }, P.distributed());
    const double mean = sim.global_count() ? compressed / double(sim.global_count()) : 0;
    if (!compression_watch_.due(mean, kWatchEvery)) return;
    double fastest = 0;
    for (std::size_t i = 0; i < P.size(); ++i)
      fastest = std::max(fastest, std::sqrt(double(P.vx()[i]) * P.vx()[i] + double(P.vy()[i]) * P.vy()[i] +
                                            double(P.vz()[i]) * P.vz()[i]));
    if (P.distributed()) fastest = comm::max(fastest);
    spdlog::warn("{}", wcsph_compression_warning(fmt::format("fix '{}' ({})", id(), style()), mean, sim.step() + 1,
                                                 c0_, fastest, sim.kernel_radius()));
  }

  // The density a particle starts from: rest density for the continuity equation (p = 0), the
  // SPH sum for the summation; of every particle, or of those `only` lists (collective: on
  // every rank, with none listed on some).
  void start_density(Simulation& sim, std::span<const std::uint32_t> only, bool every) const {
    auto& P = sim.particles();
    const std::size_t n = every ? P.size() : only.size();
    auto index = [&](std::size_t k) { return every ? k : std::size_t{only[k]}; };
    if (density_ == "continuity") {
      real* rho = P.data(rho_);
      for (std::size_t k = 0; k < n; ++k) rho[index(k)] = real(sim.rest_density());
      return;
    }
    sim.refresh_neighbors();  // collective; in a distributed run it adds ghosts, which moves the arrays
    const auto& summed = sim.summed_density();
    real* rho = P.data(rho_);
    for (std::size_t k = 0; k < n; ++k) rho[index(k)] = summed[index(k)];
  }

  void pressure_from_density(const Simulation& sim, const real* rho, real* p) const {
    const std::size_t n = sim.particles().size();
    const real rho0 = real(sim.rest_density());
    const real c2 = real(c0_ * c0_), b = real(sim.rest_density() * c0_ * c0_ / gamma_), gamma = real(gamma_);
    const bool tait = eos_ == "tait", clamp = !keep_negative_;
    for_particles(n, [&](std::size_t i) {
      const real pi = tait ? b * (std::pow(rho[i] / rho0, gamma) - 1) : c2 * (rho[i] - rho0);
      p[i] = clamp && pi < 0 ? 0 : pi;
    });
  }

  // Beyond h / c0 a sound wave outruns the kernel in one step and grows; the run would go on
  // with energy it made up (33% within 4 steps just past the limit) before any density shows it.
  void check_timestep(const Simulation& sim) const {
    const double h = sim.kernel_radius(), dt = sim.timestep();
    if (dt <= h / c0_) return;
    throw Error(fmt::format(
        "the time step {} s is beyond WCSPH's stable limit h / c0 = {:.3g} s for the sound speed {:.4g} m/s: "
        "sound waves would grow without bound (CFL: dt <= 0.15 h / c0 = {:.3g} s; fix 'cfl' chooses it)",
        dt, h / c0_, c0_, 0.15 * h / c0_));
  }

  // The weakly compressible assumption broken: stop before the pressure explodes.
  void check_density(const Simulation& sim, const real* rho) const {
    const std::size_t n = sim.particles().size();
    const double rho0 = sim.rest_density();
    std::size_t worst = n;
    double largest = max_error_;
    // Density is legitimately low at a free surface and in spray (few neighbours, or, by
    // continuity, a neighbourhood spreading out): only compression counts.
    for (std::size_t i = 0; i < n; ++i) {
      const double error = rho[i] / rho0 - 1;
      if (!(error <= largest)) worst = i, largest = std::isnan(error) ? INFINITY : error;
    }
    if (worst == n) return;
    const double h = sim.kernel_radius();
    throw Error(fmt::format(
        "particle {} has density {} kg/m^3, rho/rho0 - 1 = {:.3g} (limit {}): the fluid is no longer weakly "
        "compressible; the time step {} s is too large for the sound speed {:.4g} m/s (CFL: dt <= 0.15 h / c0 = "
        "{:.3g} s; fix 'cfl' chooses it)",
        sim.particles().ids()[worst], rho[worst], rho[worst] / rho0 - 1, max_error_, sim.timestep(), c0_,
        0.15 * h / c0_));
  }

  std::string eos_, density_;
  double gamma_, c0_, gravity_, diffusion_;
  bool keep_negative_;
  double max_error_;
  FieldId rho_ = 0, pressure_ = 0, accel_ = 0;
  bool filled_ = false;  // this run's init set every particle's density
  std::vector<real> drho_;
  CompressionWatch compression_watch_;
};

}  // namespace

void register_wcsph(StyleRegistry& r) {
  r.add({"wcsph",
         StyleKind::fix,
         "weakly compressible SPH pressure: density, equation of state, pressure acceleration (with leapfrog)",
         {ParamSpec{"eos", ParamType::String, std::string("tait"), "", "equation of state"}.one_of({"tait", "linear"}),
          ParamSpec{"gamma", ParamType::Real, 7.0, "", "Tait exponent (water: 7)"}.within(1, 20),
          ParamSpec{"sound_speed", ParamType::Real, 0.0, "m/s",
                    "c0; 0: 10 sqrt(2 g H), H the fluid's initial height (at most 1e4 m/s, faster than sound in steel)"}
              .within(0, kMostSoundSpeed),
          ParamSpec{"gravity", ParamType::Real, 9.81, "m/s^2",
                    "g in the default sound speed and the diffusion's hydrostatic part (its magnitude counts; along -z)"}
              .magnitude_at_most(kMostAcceleration),
          ParamSpec{"density", ParamType::String, std::string("summation"), "",
                    "summation: the SPH sum, walls included; continuity: integrated from the velocity divergence"}
              .one_of({"summation", "continuity"}),
          ParamSpec{"diffusion", ParamType::Real, 0.0, "",
                    "delta-SPH density diffusion delta (continuity only; 0.1 is usual, 0: none)"}
              .within(0, 1),
          {"negative_pressure", ParamType::Bool, false, "", "keep negative pressures (false: clamp them to 0)"},
          ParamSpec{"max_density_error", ParamType::Real, 0.5, "",
                    "stop the run when rho/rho0 - 1 exceeds this (compression; spray may be less dense)"}
              .above(0)},
         [](const std::string& id, const Params& p) { return std::make_unique<Wcsph>(id, p); }, nullptr});
}

}  // namespace pbf

// gravity: a constant acceleration. With an integrator that applies accelerations (the
// "acceleration" field: leapfrog, dfsph) it adds g there in the forces stage, so that the
// integrator applies it with the right weights (dfsph: after its divergence-free solve,
// before its density solve); otherwise (PBF, Macklin & Mueller's Algorithm 1) it kicks
// velocities directly, v += g dt, before the prediction.
#include "engine/core/parallel.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

namespace {

class Gravity : public Fix {
 public:
  Gravity(const std::string& id, const Params& p) : Fix(id, "gravity"), g_(p.vec3("acceleration")) {}

  // Decided when the run starts (the run loop asks for stages after every fix's init), from
  // the pipeline: a field left by a restart of another solver does not count.
  void init(Simulation& sim) override {
    const Fix* integrator = sim.integrator();
    into_accelerations_ = integrator && applies_accelerations(integrator->integration());
  }
  bool runs_distributed() const override { return true; }  // each particle on its own
  std::array<double, 3> body_acceleration() const override { return g_; }
  std::vector<Stage> stages() const override {
    return {into_accelerations_ ? Stage::forces : Stage::external_forces};
  }

  void forces(Simulation& sim) override {
    auto& P = sim.particles();
    const auto accel = P.find("acceleration");  // declared by the integrator's init
    const real gx = real(g_[0]), gy = real(g_[1]), gz = real(g_[2]);
    real *ax = P.data(*accel, 0), *ay = P.data(*accel, 1), *az = P.data(*accel, 2);
    for_particles(P.size(), [&](std::size_t i) {
      ax[i] += gx;
      ay[i] += gy;
      az[i] += gz;
    });
  }

  void external_forces(Simulation& sim) override {
    auto& P = sim.particles();
    const real dt = real(sim.timestep());
    const real gx = real(g_[0]) * dt, gy = real(g_[1]) * dt, gz = real(g_[2]) * dt;
    real *vx = P.vx(), *vy = P.vy(), *vz = P.vz();
    for_particles(P.size(), [&](std::size_t i) {
      vx[i] += gx;
      vy[i] += gy;
      vz[i] += gz;
    });
  }

 private:
  Vec3 g_;
  bool into_accelerations_ = false;
};

}  // namespace

void register_gravity(StyleRegistry& r) {
  r.add({"gravity", StyleKind::fix, "constant acceleration (gravity) added to every particle",
         {ParamSpec{"acceleration", ParamType::Vector3, Vec3{0, 0, -9.81}, "m/s^2",
                    "acceleration vector (z is up; each component at most 1000 g)"}
              .magnitude_at_most(kMostAcceleration)},
         [](const std::string& id, const Params& p) { return std::make_unique<Gravity>(id, p); }, nullptr});
}

}  // namespace pbf

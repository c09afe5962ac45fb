// leapfrog: the kick-drift-kick integrator of weakly compressible SPH.
//   predict:          v += dt/2 a_n;  x += dt v;  a = 0     (a_n: the last step's acceleration)
//   forces stage:     the force styles add a_{n+1} at the new positions
//   velocity_update:  v += dt/2 a_{n+1}
// The acceleration is a declared field ("acceleration", saved in restarts): it is the state
// one step hands to the next. The first step has no a_n: it drifts with v_0 and kicks by the
// whole dt at its end.
#include "engine/core/parallel.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/io/bytes.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

namespace {

class Leapfrog : public Fix {
 public:
  Leapfrog(const std::string& id, const Params&) : Fix(id, "leapfrog") {}

  std::vector<Stage> stages() const override { return {Stage::predict, Stage::velocity_update}; }
  // Before the walls in velocity_update, and initialised first, so that gravity sees the field.
  Role role() const override { return Role::solver; }
  bool runs_distributed() const override { return true; }  // each particle on its own
  Integration integration() const override { return Integration::accelerations; }
  std::vector<const char*> exclusive_jobs() const override { return {"time integration"}; }

  void init(Simulation& sim) override { accel_ = sim.particles().declare(kAccelerationField); }

  void predict(Simulation& sim) override {
    auto& P = sim.particles();
    const std::size_t n = P.size();
    const real dt = real(sim.timestep()), half = started_ ? dt / 2 : 0;
    real *x = P.x(), *y = P.y(), *z = P.z(), *vx = P.vx(), *vy = P.vy(), *vz = P.vz();
    real *ax = P.data(accel_, 0), *ay = P.data(accel_, 1), *az = P.data(accel_, 2);
    for_particles(n, [&](std::size_t i) {
      vx[i] += half * ax[i];
      vy[i] += half * ay[i];
      vz[i] += half * az[i];
      x[i] += dt * vx[i];
      y[i] += dt * vy[i];
      z[i] += dt * vz[i];
      ax[i] = ay[i] = az[i] = 0;
    });
  }

  void velocity_update(Simulation& sim) override {
    auto& P = sim.particles();
    const std::size_t n = P.size();
    const real dt = real(sim.timestep()), kick = started_ ? dt / 2 : dt;
    real *vx = P.vx(), *vy = P.vy(), *vz = P.vz();
    const real *ax = P.data(accel_, 0), *ay = P.data(accel_, 1), *az = P.data(accel_, 2);
    for_particles(n, [&](std::size_t i) {
      vx[i] += kick * ax[i];
      vy[i] += kick * ay[i];
      vz[i] += kick * az[i];
    });
    started_ = true;
  }

  void save_state(ByteWriter& w) const override { w.put<std::uint8_t>(started_); }
  void restore_state(ByteReader& r) override { started_ = r.get<std::uint8_t>() != 0; }

 private:
  FieldId accel_ = 0;
  bool started_ = false;
};

}  // namespace

void register_leapfrog(StyleRegistry& r) {
  r.add({"leapfrog", StyleKind::fix, "kick-drift-kick time integration of the accelerations the forces stage adds (WCSPH)",
         {}, [](const std::string& id, const Params& p) { return std::make_unique<Leapfrog>(id, p); }, nullptr});
}

}  // namespace pbf

// gravity: a constant acceleration added to every velocity, v += g dt.
#include "engine/fixes/styles.hpp"
#include "engine/simulation.hpp"

namespace pbf {

namespace {

class Gravity : public Fix {
 public:
  Gravity(const std::string& id, const Params& p) : Fix(id, "gravity"), g_(p.vec3("acceleration")) {}

  std::vector<Stage> stages() const override { return {Stage::external_forces}; }

  void external_forces(Simulation& sim) override {
    auto& P = sim.particles();
    const real dt = real(sim.timestep());
    const real gx = real(g_[0]) * dt, gy = real(g_[1]) * dt, gz = real(g_[2]) * dt;
    real *vx = P.vx(), *vy = P.vy(), *vz = P.vz();
    const std::size_t n = P.size();
#pragma omp parallel for simd schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      vx[i] += gx;
      vy[i] += gy;
      vz[i] += gz;
    }
  }

 private:
  Vec3 g_;
};

}  // namespace

void register_gravity(StyleRegistry& r) {
  r.add({"gravity", StyleKind::fix, "constant acceleration (gravity) added to every particle",
         {{"acceleration", ParamType::Vector3, Vec3{0, 0, -9.81}, "m/s^2", "acceleration vector (z is up)"}},
         [](const std::string& id, const Params& p) { return std::make_unique<Gravity>(id, p); }, nullptr});
}

}  // namespace pbf

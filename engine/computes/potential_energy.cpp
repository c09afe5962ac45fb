// potential_energy: the total potential energy in a uniform gravity field g,
// sum -m g . x (J), zero at the origin. Give it the gravity fix's `acceleration`; kinetic
// plus potential energy is then the mechanical energy, which a fluid without energy input
// (started at rest density, no vorticity confinement, walls at rest) never gains.
#include "engine/registry/builtin_styles.hpp"
#include "engine/core/parallel.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

namespace {

class PotentialEnergy : public Compute {
 public:
  PotentialEnergy(const std::string& id, const Params& p) : Compute(id, "potential_energy"), g_(p.vec3("acceleration")) {}
  std::vector<std::string> names() const override { return {"value"}; }
  std::vector<std::string> units() const override { return {"J"}; }
  bool runs_distributed() const override { return true; }
  void evaluate(Simulation& sim, std::vector<double>& values) override {
    const auto& P = sim.particles();
    values = {deterministic_sum(P.size(), [&](std::size_t i) {
      return -double(P.mass()[i]) * (g_[0] * P.x()[i] + g_[1] * P.y()[i] + g_[2] * P.z()[i]);
    }, P.distributed())};
  }

 private:
  Vec3 g_;
};

}  // namespace

void register_compute_potential_energy(StyleRegistry& r) {
  r.add({"potential_energy",
         StyleKind::compute,
         "total potential energy in uniform gravity, sum -m g . x (J)",
         {ParamSpec{"acceleration", ParamType::Vector3, Vec3{0, 0, -9.81}, "m/s^2",
                    "the gravity it is the potential of (give the gravity fix's)"}},
         nullptr, make_compute<PotentialEnergy>(),
         "one, the energy (J)"});
}

}  // namespace pbf

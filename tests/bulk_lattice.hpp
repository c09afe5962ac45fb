#pragma once
// A block of particles on add_lattice's cubic lattice, and the sums over the infinite lattice
// that a style's SPH sums equal at the block's bulk particles. A particle whose sum reaches
// only particles with full neighbourhoods (far enough inside every face) sees the infinite
// lattice: the mass rule gives every such neighbour the density rho0 and the volume
// V = m / rho = 1 / sum_j W(r_j), and a pair sum there is one of these lattice sums. Tests
// predict a style's result in the bulk from them, to rounding.
#include <cmath>
#include <cstddef>
#include <functional>

#include "engine/core/fix.hpp"
#include "engine/core/simulation.hpp"
#include "engine/sph/kernels.hpp"
#include "engine/sph/lattice.hpp"
#include "test_util.hpp"

namespace pbf::test {

// f(rx, ry, rz, r2) summed over the sites r != 0 of the infinite cubic lattice of spacing s
// within the kernel's support (|r| < h).
template <class F>
double lattice_sum(double s, const Kernels& K, F f) {
  const int reach = static_cast<int>(std::ceil(double(K.h) / s));
  double sum = 0;
  for (int k = -reach; k <= reach; ++k)
    for (int j = -reach; j <= reach; ++j)
      for (int i = -reach; i <= reach; ++i) {
        const double rx = i * s, ry = j * s, rz = k * s, r2 = rx * rx + ry * ry + rz * rz;
        if (r2 > 0 && r2 < double(K.h2)) sum += f(rx, ry, rz, r2);
      }
  return sum;
}

// The volume m / rho of a particle with a full neighbourhood: 1 / sum_j W(r_j), j = i included.
inline double bulk_volume(double s, const Kernels& K) {
  return 1 / (double(K.W(0)) + lattice_sum(s, K, [&](double, double, double, double r2) { return K.W(real(r2)); }));
}

// kappa = -1/3 sum_j V g(r_j) r_j^2 (gradW = g r_vec): on the lattice the SPH gradient
// sum_j V (f_j - f_i) gradW_ij of a linear field f is kappa grad f (cubic symmetry makes
// sum_j V g r_a r_b = -kappa delta_ab); 0.950 at h = 2s.
inline double gradient_norm(double s, const Kernels& K) {
  const double V = bulk_volume(s, K);
  return -V / 3 * lattice_sum(s, K, [&](double, double, double, double r2) { return K.grad_factor(real(r2)) * r2; });
}

// The Laplacian viscosity's lattice factor, -V sum_j g r_j^2 r_z^2 / (r_j^2 + 0.01 h^2): Morris's
// sum 2 V sum_j (-g) r^2 / (r^2 + eta^2) (u_j - u_i) of a quadratic field u = z^2 / 2 (whose
// Laplacian is 1) on the lattice, which sph_viscosity divides its sum by; 0.922 at h = 2s.
inline double laplacian_factor(double s, const Kernels& K) {
  const double V = bulk_volume(s, K), eta2 = 0.01 * double(K.h2);
  return -V * lattice_sum(s, K, [&](double, double, double rz, double r2) {
    return K.grad_factor(real(r2)) * r2 * rz * rz / (r2 + eta2);
  });
}

// The rounding of an SPH pair sum at a bulk particle of a block whose sites reach L = reach s
// from the origin, relative to the sum of its terms' sizes. Positions are stored to
// u |x| <= u L, so an offset r_j (|r_j| >= s) errs by up to 2 u L / s of itself; the kernel
// factor g(r) ~ (1 - r/h)^3 magnifies an error of r by 3 r / (h - r) <= 20 (the farthest
// neighbour at h = 2s, r = sqrt(3) s), and the volume 1 / sum W by at most 25 (|dlnW/dlnr|
// at the same r). A term with one g, one V and up to two factors of r thus errs by at most
// (2 + 2 + 2 * 20 + 2 * 25) u L / s < 100 u L / s, and the 27-term sums add 60 u.
inline double pair_sum_rounding(double reach) { return (100 * reach + 60) * kUnitRoundoff; }

// A block of nx x ny x nz particles at spacing s centred on the origin, h = 2s (the engine's
// usual ratio), at rest, in an empty domain ten times its size: no walls, no gravity.
inline void centred_block(Simulation& sim, const int n[3], double s, double dt) {
  Domain d;
  for (int a = 0; a < 3; ++a) d.lo[a] = -5 * n[a] * s, d.hi[a] = 5 * n[a] * s;
  sim.set_domain(d);
  sim.set_kernel_radius(2 * s);
  sim.set_timestep(dt);
  const double lo[3] = {-n[0] * s / 2, -n[1] * s / 2, -n[2] * s / 2}, hi[3] = {n[0] * s / 2, n[1] * s / 2, n[2] * s / 2};
  const double rest[3] = {0, 0, 0};
  add_lattice(sim, lo, hi, s, rest);
}

// Whether the site at (x, y, z) of the centred block lies at least `depth` from every site
// the block lacks: a sum reaching `depth` from it sees the infinite lattice. (The block's
// sites end at +-(n - 1) s / 2 along each axis, so the first missing ones are at +-(n + 1) s / 2.
// A site exactly `depth` away counts: the kernel vanishes at h with its gradient, so a
// position's rounding, far below the 1e-6 s allowed, adds nothing to the sums.)
inline bool in_bulk(const int n[3], double s, double depth, double x, double y, double z) {
  const double c[3] = {x, y, z};
  for (int a = 0; a < 3; ++a)
    if ((n[a] + 1) * s / 2 - std::fabs(c[a]) < depth - 1e-6 * s) return false;
  return true;
}

// A test fix that sets every velocity to field(x, y, z) in one stage, so that the fix under
// test (later in the stage, or in a later stage) sees that field on particles the integrator
// has not moved (they start at rest, so its drift is zero).
class SetVelocities : public Fix {
 public:
  using Field = std::function<void(double x, double y, double z, double v[3])>;
  SetVelocities(Stage stage, Field field) : Fix("set_velocities", "test"), stage_(stage), field_(std::move(field)) {}

  std::vector<Stage> stages() const override { return {stage_}; }
  void forces(Simulation& sim) override { set(sim); }
  void velocity_update(Simulation& sim) override { set(sim); }

 private:
  void set(Simulation& sim) const {
    auto& P = sim.particles();
    for (std::size_t i = 0; i < P.size(); ++i) {
      double v[3];
      field_(P.x()[i], P.y()[i], P.z()[i], v);
      P.vx()[i] = real(v[0]), P.vy()[i] = real(v[1]), P.vz()[i] = real(v[2]);
    }
  }

  Stage stage_;
  Field field_;
};

}  // namespace pbf::test

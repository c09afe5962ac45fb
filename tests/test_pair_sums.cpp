// The vectorised pair sums (engine/sph/pair_sums.hpp) against a plain double-precision loop
// over all pairs, at every vector width this machine offers. The kernel's own test checks the
// scalar kernel only; these catch what goes wrong inside the vector loops: a flipped gradient
// sign, a wrong kernel constant, a neighbour dropped from a list's tail.
//
// The particles: a jittered 6 x 6 x 6 lattice (spacing h/2, so about 33 neighbours in the bulk
// and every list length modulo 16 occurs: tails of every size at every width), masses equal or
// varied by +-50%, and satellites at 0.99 h from a lattice particle (pairs near the support's
// edge, where 1 - q cancels).
//
// Tolerance. For a sum of n terms, |fl(sum) - sum| <= (n - 1) eps sum|t_j|. Each term is a
// kernel factor times a few inputs; the kernel's error is not relative to its value near the
// edge (there 1 - q comes from a rounded q) but is at most a few tens of eps times the kernel's
// largest value, W(0) = c or |g(0)| = 20 c / h^2. So with T_j the term's bound (its kernel
// factor replaced by that largest value),
//   |engine - exact| <= (n + 64) eps sum_j T_j,
// 64 being a generous count of the roundings in one term (about 10, the worst amplified 3x by
// (1 - q)^3). The reference is double, which in a double build is as rounded as the engine:
// the bound allows twice that. Measured in single precision: the largest error is 1/800 of
// the bound; a flipped gradient errs by up to 1000 bounds, a neighbour dropped from each
// list's tail by up to 100, the kernel's constant off by 0.1% by 2 to 3.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "engine/core/vectors.hpp"
#include "engine/sph/neighbor_grid.hpp"
#include "engine/sph/pair_sums.hpp"

using namespace pbf;

namespace {

constexpr double kH = 0.02, kSpacing = kH / 2;

// Particles and the per-particle inputs of the sums, in `real` as the engine holds them.
struct Cloud {
  std::vector<real> x, y, z, m, vx, vy, vz, volume, f, lambda;
  std::size_t size() const { return x.size(); }
};

// Uniform in [0, 1): mt19937's sequence is fixed by the standard, unlike the distributions.
double uniform(std::mt19937& rng) { return rng() / 4294967296.0; }

Cloud make_cloud(bool equal_masses) {
  std::mt19937 rng(31);
  Cloud c;
  auto add = [&](double px, double py, double pz) {
    const double m = 1000 * std::pow(kSpacing, 3);
    c.x.push_back(real(px)), c.y.push_back(real(py)), c.z.push_back(real(pz));
    c.m.push_back(real(equal_masses ? m : m * (0.5 + uniform(rng))));
    c.vx.push_back(real(uniform(rng) - 0.5)), c.vy.push_back(real(uniform(rng) - 0.5));
    c.vz.push_back(real(uniform(rng) - 0.5));
    c.volume.push_back(real(std::pow(kSpacing, 3) * (0.8 + 0.4 * uniform(rng))));
    c.f.push_back(real(1000 * uniform(rng)));
    c.lambda.push_back(real(-1e-5 * uniform(rng) + 2e-6));
  };
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      for (int k = 0; k < 6; ++k)  // jitter up to a quarter spacing along each axis
        add(0.02 + kSpacing * (i + 0.5 * uniform(rng) - 0.25), 0.02 + kSpacing * (j + 0.5 * uniform(rng) - 0.25),
            0.02 + kSpacing * (k + 0.5 * uniform(rng) - 0.25));
  // Satellites just inside the support of three corner particles (lattice index 36 i + 6 j + k),
  // out along the diagonal, out of reach of the rest.
  const struct { std::size_t i; double out[3]; } corners[] = {{0, {-1, -1, -1}}, {5, {-1, -1, 1}}, {215, {1, 1, 1}}};
  for (const auto& [i, out] : corners) {
    const double d = 0.99 * kH / std::sqrt(3.0);
    add(c.x[i] + out[0] * d, c.y[i] + out[1] * d, c.z[i] + out[2] * d);
  }
  return c;
}

// The kernel of docs/physics.md in double: W = c (1 - q)^4 (1 + 4q), gradW = g r_vec with
// g = -20 c (1 - q)^3 / h^2, c = 21 / (2 pi h^3); zero from r = h on.
const double kC = 21 / (2 * std::numbers::pi * kH * kH * kH), kG0 = 20 * kC / (kH * kH);
double W(double r) { return r < kH ? kC * std::pow(1 - r / kH, 4) * (1 + 4 * r / kH) : 0; }
double g(double r) { return r < kH ? -kG0 * std::pow(1 - r / kH, 3) : 0; }

// Calls pair(j, d, r) for every j != i within h of particle i, d = x_i - x_j, all in double.
template <class Pair>
void for_pairs(const Cloud& c, std::size_t i, Pair&& pair) {
  for (std::size_t j = 0; j < c.size(); ++j) {
    const double d[3] = {double(c.x[i]) - c.x[j], double(c.y[i]) - c.y[j], double(c.z[i]) - c.z[j]};
    const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (j != i && r < kH) pair(j, d, r);
  }
}

constexpr double kEps = std::numeric_limits<real>::epsilon();

// One component of a sum, per particle: the exact value, the sum of its terms' bounds T_j and
// the number of terms.
struct Reference {
  std::vector<double> value, bound;
  std::vector<int> terms;
  explicit Reference(std::size_t n) : value(n), bound(n), terms(n) {}
  std::vector<double> tolerance() const {
    std::vector<double> tol(value.size());
    for (std::size_t i = 0; i < tol.size(); ++i) tol[i] = 2 * (terms[i] + 64) * kEps * bound[i];
    return tol;
  }
};

// The references of a vector sum over pairs: term(i, j, d, r, t, T) gives the pair's term t and
// its bound T, component by component.
template <class Term>
std::vector<Reference> vector_references(const Cloud& c, Term&& term) {
  std::vector<Reference> ref(3, Reference(c.size()));
  for (std::size_t i = 0; i < c.size(); ++i)
    for_pairs(c, i, [&](std::size_t j, const double d[3], double r) {
      double t[3], T[3];
      term(i, j, d, r, t, T);
      for (int a = 0; a < 3; ++a) ref[a].value[i] += t[a], ref[a].bound[i] += T[a], ++ref[a].terms[i];
    });
  return ref;
}

// What one output of a pass must be, per particle, within a tolerance.
struct Expected {
  std::string name;
  std::vector<double> value, tolerance;
};

// The three components of a vector sum.
std::vector<Expected> xyz(const std::string& name, const std::vector<Reference>& ref) {
  std::vector<Expected> out;
  for (int a = 0; a < 3; ++a) out.push_back({name + "xyz"[a], ref[a].value, ref[a].tolerance()});
  return out;
}

// Runs pass(outputs) at each vector width of this machine: each output must be as expected
// (in order), and have the same bits at each width (docs/design.md, "Vectors").
template <class Pass>
void at_every_width(const std::vector<Expected>& expected, Pass&& pass) {
  const auto widths = vector_choices();
  ASSERT_FALSE(widths.empty());
  std::vector<std::vector<real>> widest;
  std::set<std::string> used;  // the instruction sets the widths chose: one each, or the loop tests less than it says
  for (const std::string& width : widths) {
    limit_vectors(width);
    used.insert(vectors_in_use());
    SCOPED_TRACE("vectors '" + width + "' (" + vectors_in_use() + ")");
    std::vector<std::vector<real>> got(expected.size(), std::vector<real>(expected[0].value.size()));
    pass(got);
    for (std::size_t k = 0; k < got.size(); ++k) {
      const Expected& e = expected[k];
      for (std::size_t i = 0, wrong = 0; i < got[k].size() && wrong < 5; ++i)
        if (!(std::abs(got[k][i] - e.value[i]) <= e.tolerance[i]))
          ++wrong, ADD_FAILURE() << e.name << " of particle " << i << ": " << got[k][i] << ", the reference "
                                 << e.value[i] << " (tolerance " << e.tolerance[i] << ")";
      if (!widest.empty()) EXPECT_TRUE(got[k] == widest[k]) << e.name << " differs from the widest vectors' bits";
    }
    if (widest.empty()) widest = got;
  }
  limit_vectors("auto");
  EXPECT_EQ(used.size(), widths.size());
}

// The engine's inputs for a cloud: the grid with its lists, and the pass input.
struct Engine {
  const Cloud& c;
  NeighborGrid grid;
  Kernels kernels{kH};
  explicit Engine(const Cloud& cloud) : c(cloud) {
    Domain domain;
    for (int a = 0; a < 3; ++a) domain.lo[a] = 0, domain.hi[a] = 0.1;
    grid.bin(c.x.data(), c.y.data(), c.z.data(), c.size(), domain, kH);
    grid.build_lists(c.x.data(), c.y.data(), c.z.data(), kH);
  }
  PairInput input() const {
    const real common_mass = uniform_mass(c.m.data(), c.size());
    return {grid, c.x.data(), c.y.data(), c.z.data(), c.m.data(), common_mass, kernels, c.size()};
  }
};

// The references of the density and constraint sums: rho, grad_x, grad_y, grad_z, grad_sq.
std::vector<Reference> constraint_references(const Cloud& c, double inv_rho0) {
  std::vector<Reference> ref(5, Reference(c.size()));
  for (std::size_t i = 0; i < c.size(); ++i) {
    ref[0].value[i] = ref[0].bound[i] = double(c.m[i]) * kC;
    for_pairs(c, i, [&](std::size_t j, const double d[3], double r) {
      const double gj = c.m[j] * inv_rho0 * g(r), gj_bound = c.m[j] * inv_rho0 * kG0;
      ref[0].value[i] += c.m[j] * W(r);
      ref[0].bound[i] += c.m[j] * kC;
      for (int a = 0; a < 3; ++a) {
        ref[1 + a].value[i] += gj * d[a];
        ref[1 + a].bound[i] += gj_bound * r;
      }
      ref[4].value[i] += gj * gj * r * r;
      ref[4].bound[i] += gj_bound * gj_bound * r * r;
      for (Reference& each : ref) ++each.terms[i];
    });
  }
  return ref;
}

}  // namespace

// The particle set is what the header says: lists with tails of every length, and pairs near h.
TEST(PairSums, TheParticleSetHasTailsOfEveryLengthAndPairsNearTheEdge) {
  const Cloud c = make_cloud(true);
  Engine engine(c);
  std::set<std::uint32_t> tails;
  for (std::size_t i = 0; i < c.size(); ++i) tails.insert(engine.grid.count(i) % 16);
  EXPECT_EQ(tails.size(), 16u);
  int near_edge = 0;
  for (std::size_t i = 0; i < c.size(); ++i)
    for_pairs(c, i, [&](std::size_t, const double*, double r) { near_edge += r > 0.98 * kH; });
  EXPECT_GE(near_edge, 6);  // the three satellites' pairs, both ways, and some of the lattice's
}

TEST(PairSums, DensityMatchesTheReference) {
  for (bool equal : {true, false}) {
    SCOPED_TRACE(equal ? "equal masses" : "varied masses");
    const Cloud c = make_cloud(equal);
    Engine engine(c);
    EXPECT_EQ(uniform_mass(c.m.data(), c.size()) > 0, equal);  // both of the passes' mass paths
    const Reference rho = constraint_references(c, 1)[0];
    at_every_width({{"rho", rho.value, rho.tolerance()}},
                   [&](auto& out) { density_sums(engine.input(), 0, c.size(), out[0].data()); });
  }
}

TEST(PairSums, ConstraintSumsMatchTheReference) {
  const real inv_rho0 = real(1e-3);
  for (bool equal : {true, false}) {
    SCOPED_TRACE(equal ? "equal masses" : "varied masses");
    const Cloud c = make_cloud(equal);
    Engine engine(c);
    const auto ref = constraint_references(c, inv_rho0);
    std::vector<Expected> expected = xyz("grad_", {ref[1], ref[2], ref[3]});
    expected.insert(expected.begin(), {"rho", ref[0].value, ref[0].tolerance()});
    expected.push_back({"grad_sq", ref[4].value, ref[4].tolerance()});
    at_every_width(expected, [&](auto& out) {
      constraint_sums(engine.input(), 0, c.size(), inv_rho0, out[0].data(), out[1].data(), out[2].data(),
                      out[3].data(), out[4].data());
    });
  }
}

// d_i = inv_rho0 sum_j m_j (lambda_i + lambda_j + s_ij) gradW_ij, s_ij = -k (W_ij / W(dq))^n;
// without and with the artificial pressure.
TEST(PairSums, ConstraintCorrectionsMatchTheReference) {
  const real inv_rho0 = real(1e-3), inv_wdq = real(1 / W(0.2 * kH));
  for (bool equal : {true, false})
    for (const real scale : {real(0), real(1e-6)}) {
      SCOPED_TRACE(std::string(equal ? "equal masses" : "varied masses") + (scale > 0 ? ", s_corr" : ""));
      const Cloud c = make_cloud(equal);
      Engine engine(c);
      const int n = 4;
      const auto ref = vector_references(c, [&](auto i, auto j, const double d[3], double r, double* t, double* T) {
        const double s = -scale * std::pow(W(r) * inv_wdq, n), s_bound = scale * std::pow(kC * inv_wdq, n);
        const double factor = double(c.lambda[i]) + c.lambda[j] + s;
        const double bound = std::abs(double(c.lambda[i])) + std::abs(double(c.lambda[j])) + s_bound;
        const double mj = double(inv_rho0) * c.m[j];
        for (int a = 0; a < 3; ++a) t[a] = mj * factor * g(r) * d[a], T[a] = mj * bound * kG0 * r;
      });
      at_every_width(xyz("d", ref), [&](auto& out) {
        constraint_corrections(engine.input(), 0, c.size(), c.lambda.data(), inv_rho0, scale, inv_wdq, n,
                               out[0].data(), out[1].data(), out[2].data());
      });
    }
}

// w_i = sum_j V_j gradW_ij x (v_j - v_i), and |w_i|.
TEST(PairSums, CurlMatchesTheReference) {
  const Cloud c = make_cloud(false);
  Engine engine(c);
  const auto ref = vector_references(c, [&](auto i, auto j, const double d[3], double r, double* t, double* T) {
    const double u[3] = {double(c.vx[j]) - c.vx[i], double(c.vy[j]) - c.vy[i], double(c.vz[j]) - c.vz[i]};
    const double G = c.volume[j] * g(r), u_norm = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (int a = 0; a < 3; ++a) {
      const int b = (a + 1) % 3, e = (a + 2) % 3;
      t[a] = G * (d[b] * u[e] - d[e] * u[b]);
      T[a] = 2 * c.volume[j] * kG0 * r * u_norm;  // two products, each at most |r||u|
    }
  });
  // |w|: off by at most the components' errors, and a few roundings of its own.
  std::vector<Expected> expected = xyz("w", ref);
  Expected magnitude{"|w|", std::vector<double>(c.size()), std::vector<double>(c.size())};
  for (std::size_t i = 0; i < c.size(); ++i) {
    magnitude.value[i] = std::hypot(ref[0].value[i], ref[1].value[i], ref[2].value[i]);
    magnitude.tolerance[i] = expected[0].tolerance[i] + expected[1].tolerance[i] + expected[2].tolerance[i] +
                             4 * kEps * magnitude.value[i];
  }
  expected.push_back(magnitude);
  at_every_width(expected, [&](auto& out) {
    curl_sums(engine.input(), 0, c.size(), c.volume.data(), c.vx.data(), c.vy.data(), c.vz.data(), out[0].data(),
              out[1].data(), out[2].data(), out[3].data());
  });
}

// e_i = sum_j V_j (f_j - f_i) gradW_ij.
TEST(PairSums, GradientMatchesTheReference) {
  const Cloud c = make_cloud(false);
  Engine engine(c);
  const auto ref = vector_references(c, [&](auto i, auto j, const double d[3], double r, double* t, double* T) {
    const double df = double(c.f[j]) - c.f[i];
    for (int a = 0; a < 3; ++a) t[a] = c.volume[j] * df * g(r) * d[a], T[a] = c.volume[j] * std::abs(df) * kG0 * r;
  });
  at_every_width(xyz("e", ref), [&](auto& out) {
    gradient_sums(engine.input(), 0, c.size(), c.volume.data(), c.f.data(), out[0].data(), out[1].data(),
                  out[2].data());
  });
}

// d_i = sum_j V_j (v_j - v_i) W_ij.
TEST(PairSums, SmoothingMatchesTheReference) {
  const Cloud c = make_cloud(false);
  Engine engine(c);
  const std::vector<real>* v[3] = {&c.vx, &c.vy, &c.vz};
  const auto ref = vector_references(c, [&](auto i, auto j, const double*, double r, double* t, double* T) {
    for (int a = 0; a < 3; ++a) {
      const double du = double((*v[a])[j]) - (*v[a])[i];
      t[a] = c.volume[j] * du * W(r), T[a] = c.volume[j] * std::abs(du) * kC;
    }
  });
  at_every_width(xyz("d", ref), [&](auto& out) {
    smoothing_sums(engine.input(), 0, c.size(), c.volume.data(), c.vx.data(), c.vy.data(), c.vz.data(),
                   out[0].data(), out[1].data(), out[2].data());
  });
}

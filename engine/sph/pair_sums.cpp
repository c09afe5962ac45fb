// The neighbour sums of engine/sph/pair_sums.hpp, written once with Highway's portable
// vectors and compiled for each x86-64 vector width (SSE4, AVX2, AVX-512, and a fallback
// without vectors); the widest the machine has is chosen at run time. For particle i, each
// vector step gathers the positions (and whatever else the sum needs) of the next N
// neighbours in its list; lanes past the list's end read valid indices (the lists are padded)
// and get zero mass, so they add exactly nothing.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "engine/sph/pair_sums.cpp"
#include "engine/sph/pair_sums.hpp"

#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "engine/sph/neighbor_grid.hpp"

HWY_BEFORE_NAMESPACE();
namespace pbf {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::ScalableTag<real>;
using V = hn::Vec<D>;
using Index = hn::Vec<hn::RebindToSigned<D>>;

// N neighbour indices as the signed lanes a gather of `real` takes.
template <class DR>
HWY_INLINE hn::Vec<hn::RebindToSigned<DR>> load_indices(DR /*d*/, const std::uint32_t* p) {
  const hn::RebindToSigned<DR> di;
  if constexpr (sizeof(hn::TFromD<DR>) == 4) {
    return hn::BitCast(di, hn::LoadU(hn::RebindToUnsigned<DR>(), p));
  } else {
    const hn::Rebind<std::int32_t, DR> d32;
    return hn::PromoteTo(di, hn::LoadU(d32, reinterpret_cast<const std::int32_t*>(p)));
  }
}

// The masses to gather, or null when they are all in_.uniform_mass.
HWY_INLINE const real* masses(const PairInput& in) { return in.uniform_mass > 0 ? nullptr : in.m; }

// A sum over a particle's neighbours in kLanes lanes (one AVX-512 vector's worth), held in
// as many vectors as this target needs: neighbour k of the list goes to lane k mod kLanes,
// and total() adds the lanes in one fixed tree (lane l with lane l + half, halving). So the
// terms are grouped the same way whatever the machine's vector width (SSE4, AVX2, AVX-512 or
// none): every sum, and with it every run, has the same bits on any x86-64 machine.
constexpr std::size_t kWidth = hn::MaxLanes(D());
constexpr std::size_t kLanes = 64 / sizeof(real);
constexpr std::size_t kVectors = kLanes / kWidth;
static_assert(kVectors * kWidth == kLanes, "a target wider than 512 bits needs more lanes");

template <class DV>
HWY_INLINE real fold(DV, hn::Vec<DV> v) {
  if constexpr (hn::MaxLanes(DV()) == 1) {
    return hn::GetLane(v);
  } else {
    const hn::Half<DV> dh;  // unqualified: found on instantiation (a target without halves has none)
    return fold(dh, hn::Add(LowerHalf(dh, v), UpperHalf(dh, v)));
  }
}

struct Sum {
  V part[kVectors];
  Sum() {
    for (V& p : part) p = hn::Zero(D());
  }
  void add(std::size_t v, V term) { part[v] = hn::Add(part[v], term); }
  real total() {
    for (std::size_t width = kVectors; width > 1; width /= 2)
      for (std::size_t v = 0; v < width / 2; ++v) part[v] = hn::Add(part[v], part[v + width / 2]);
    return fold(D(), part[0]);
  }
};

// The kernel of engine/sph/kernels.hpp on vectors of squared distances; (1 - q) is clamped
// at zero, so pairs at or beyond h get W = gradW = 0 as there.
struct KernelVectors {
  V inv_h, coef, grad_coef, one, four, zero;
  explicit KernelVectors(const Kernels& K)
      : inv_h(hn::Set(D(), K.inv_h)),
        coef(hn::Set(D(), K.coef)),
        grad_coef(hn::Set(D(), -20 * K.coef * K.inv_h * K.inv_h)),
        one(hn::Set(D(), real(1))),
        four(hn::Set(D(), real(4))),
        zero(hn::Zero(D())) {}
  V W(V r2) const {
    const V q = hn::Mul(hn::Sqrt(r2), inv_h), d = hn::Max(hn::Sub(one, q), zero), d2 = hn::Mul(d, d);
    return hn::Mul(hn::Mul(coef, hn::Mul(d2, d2)), hn::Add(one, hn::Mul(four, q)));
  }
  V grad_factor(V r2) const {
    const V d = hn::Max(hn::Sub(one, hn::Mul(hn::Sqrt(r2), inv_h)), zero);
    return hn::Mul(grad_coef, hn::Mul(hn::Mul(d, d), d));
  }
  void both(V r2, V& w, V& g) const {
    const V q = hn::Mul(hn::Sqrt(r2), inv_h), d = hn::Max(hn::Sub(one, q), zero), d3 = hn::Mul(hn::Mul(d, d), d);
    w = hn::Mul(hn::Mul(coef, hn::Mul(d3, d)), hn::Add(one, hn::Mul(four, q)));
    g = hn::Mul(grad_coef, d3);
  }
};

// One vector of particle i's neighbours: their indices, x_i - x_j, |x_i - x_j|^2, and their
// weight (mass or volume; zero in the lanes past the list's end).
struct Neighbors {
  Index j;
  V dx, dy, dz, r2, weight;
};

// Calls body(v, Neighbors) for each vector of particle i's neighbours, in list order, v being
// the vector's place in a Sum; the weight is weights[j], or `uniform` for every j when weights
// is null. A vector wholly past the list's end would add zeros, which change no sum: skipped.
template <class Body>
HWY_INLINE void for_neighbor_vectors(const PairInput& in, std::size_t i, const real* weights, real uniform,
                                     Body&& body) {
  const D d;
  const std::size_t count = in.grid.count(i);
  const std::uint32_t* list = in.grid.neighbors(i);
  const V xi = hn::Set(d, in.x[i]), yi = hn::Set(d, in.y[i]), zi = hn::Set(d, in.z[i]);
  for (std::size_t k = 0; k < count; k += kLanes)
    for (std::size_t v = 0; v < kVectors && k + v * kWidth < count; ++v) {
      const std::size_t at = k + v * kWidth;
      Neighbors nb;
      nb.j = load_indices(d, list + at);
      nb.dx = hn::Sub(xi, hn::GatherIndex(d, in.x, nb.j));
      nb.dy = hn::Sub(yi, hn::GatherIndex(d, in.y, nb.j));
      nb.dz = hn::Sub(zi, hn::GatherIndex(d, in.z, nb.j));
      nb.r2 = hn::Add(hn::Add(hn::Mul(nb.dx, nb.dx), hn::Mul(nb.dy, nb.dy)), hn::Mul(nb.dz, nb.dz));
      const auto valid = hn::FirstN(d, count - at);
      nb.weight = hn::IfThenElseZero(valid, weights ? hn::GatherIndex(d, weights, nb.j) : hn::Set(d, uniform));
      body(v, nb);
    }
}

void DensitySums(const PairInput& in, std::size_t begin, std::size_t end, real* rho) {
  const KernelVectors K(in.kernels);
  const real w0 = in.kernels.W(0);
  for (std::size_t i = begin; i < end; ++i) {
    Sum sum;
    for_neighbor_vectors(in, i, masses(in), in.uniform_mass,
                         [&](std::size_t v, const Neighbors& nb) { sum.add(v, hn::Mul(nb.weight, K.W(nb.r2))); });
    rho[i] = in.m[i] * w0 + sum.total();
  }
}

void ConstraintSums(const PairInput& in, std::size_t begin, std::size_t end, real inv_rho0, real* rho, real* grad_x,
                    real* grad_y, real* grad_z, real* grad_sq) {
  const D d;
  const KernelVectors K(in.kernels);
  const real w0 = in.kernels.W(0);
  const V inv_rho0_v = hn::Set(d, inv_rho0);
  for (std::size_t i = begin; i < end; ++i) {
    Sum density, gx, gy, gz, sq;
    for_neighbor_vectors(in, i, masses(in), in.uniform_mass, [&](std::size_t v, const Neighbors& nb) {
      V w, gw;
      K.both(nb.r2, w, gw);
      density.add(v, hn::Mul(nb.weight, w));
      const V g = hn::Mul(hn::Mul(nb.weight, inv_rho0_v), gw);  // grad_j C_i = -g r_ij
      gx.add(v, hn::Mul(g, nb.dx));
      gy.add(v, hn::Mul(g, nb.dy));
      gz.add(v, hn::Mul(g, nb.dz));
      sq.add(v, hn::Mul(hn::Mul(g, g), nb.r2));
    });
    rho[i] = in.m[i] * w0 + density.total();
    grad_x[i] = gx.total();
    grad_y[i] = gy.total();
    grad_z[i] = gz.total();
    grad_sq[i] = sq.total();
  }
}

void ConstraintCorrections(const PairInput& in, std::size_t begin, std::size_t end, const real* lambda, real inv_rho0,
                           real scorr_scale, real inv_wdq, int scorr_n, real* dx, real* dy, real* dz) {
  const D d;
  const KernelVectors K(in.kernels);
  const V inv_rho0_v = hn::Set(d, inv_rho0), minus_scale = hn::Set(d, -scorr_scale), inv_wdq_v = hn::Set(d, inv_wdq);
  for (std::size_t i = begin; i < end; ++i) {
    const V lambda_i = hn::Set(d, lambda[i]);
    Sum cx, cy, cz;
    for_neighbor_vectors(in, i, masses(in), in.uniform_mass, [&](std::size_t v, const Neighbors& nb) {
      V factor = hn::Add(lambda_i, hn::GatherIndex(d, lambda, nb.j));
      if (scorr_scale > 0) {  // the artificial pressure
        const V ratio = hn::Mul(K.W(nb.r2), inv_wdq_v);
        V power = ratio;
        for (int e = 1; e < scorr_n; ++e) power = hn::Mul(power, ratio);
        factor = hn::Add(factor, hn::Mul(minus_scale, power));
      }
      const V g = hn::Mul(hn::Mul(hn::Mul(nb.weight, inv_rho0_v), factor), K.grad_factor(nb.r2));
      cx.add(v, hn::Mul(g, nb.dx));
      cy.add(v, hn::Mul(g, nb.dy));
      cz.add(v, hn::Mul(g, nb.dz));
    });
    dx[i] = cx.total();
    dy[i] = cy.total();
    dz[i] = cz.total();
  }
}

void CurlSums(const PairInput& in, std::size_t begin, std::size_t end, const real* volume, const real* vx,
              const real* vy, const real* vz, real* wx, real* wy, real* wz, real* magnitude) {
  const D d;
  const KernelVectors K(in.kernels);
  for (std::size_t i = begin; i < end; ++i) {
    const V vxi = hn::Set(d, vx[i]), vyi = hn::Set(d, vy[i]), vzi = hn::Set(d, vz[i]);
    Sum ax, ay, az;
    for_neighbor_vectors(in, i, volume, 0, [&](std::size_t v, const Neighbors& nb) {
      const V g = hn::Mul(nb.weight, K.grad_factor(nb.r2));
      const V gx = hn::Mul(g, nb.dx), gy = hn::Mul(g, nb.dy), gz = hn::Mul(g, nb.dz);
      const V ux = hn::Sub(hn::GatherIndex(d, vx, nb.j), vxi), uy = hn::Sub(hn::GatherIndex(d, vy, nb.j), vyi),
              uz = hn::Sub(hn::GatherIndex(d, vz, nb.j), vzi);
      ax.add(v, hn::Sub(hn::Mul(gy, uz), hn::Mul(gz, uy)));
      ay.add(v, hn::Sub(hn::Mul(gz, ux), hn::Mul(gx, uz)));
      az.add(v, hn::Sub(hn::Mul(gx, uy), hn::Mul(gy, ux)));
    });
    const real w[3] = {ax.total(), ay.total(), az.total()};
    wx[i] = w[0];
    wy[i] = w[1];
    wz[i] = w[2];
    magnitude[i] = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  }
}

void GradientSums(const PairInput& in, std::size_t begin, std::size_t end, const real* volume, const real* f, real* ex,
                  real* ey, real* ez) {
  const D d;
  const KernelVectors K(in.kernels);
  for (std::size_t i = begin; i < end; ++i) {
    const V fi = hn::Set(d, f[i]);
    Sum ax, ay, az;
    for_neighbor_vectors(in, i, volume, 0, [&](std::size_t v, const Neighbors& nb) {
      const V difference = hn::Sub(hn::GatherIndex(d, f, nb.j), fi);
      const V g = hn::Mul(hn::Mul(nb.weight, difference), K.grad_factor(nb.r2));
      ax.add(v, hn::Mul(g, nb.dx));
      ay.add(v, hn::Mul(g, nb.dy));
      az.add(v, hn::Mul(g, nb.dz));
    });
    ex[i] = ax.total();
    ey[i] = ay.total();
    ez[i] = az.total();
  }
}

void SmoothingSums(const PairInput& in, std::size_t begin, std::size_t end, const real* volume, const real* vx,
                   const real* vy, const real* vz, real* dx, real* dy, real* dz) {
  const D d;
  const KernelVectors K(in.kernels);
  for (std::size_t i = begin; i < end; ++i) {
    const V vxi = hn::Set(d, vx[i]), vyi = hn::Set(d, vy[i]), vzi = hn::Set(d, vz[i]);
    Sum ax, ay, az;
    for_neighbor_vectors(in, i, volume, 0, [&](std::size_t v, const Neighbors& nb) {
      const V w = hn::Mul(nb.weight, K.W(nb.r2));
      ax.add(v, hn::Mul(w, hn::Sub(hn::GatherIndex(d, vx, nb.j), vxi)));
      ay.add(v, hn::Mul(w, hn::Sub(hn::GatherIndex(d, vy, nb.j), vyi)));
      az.add(v, hn::Mul(w, hn::Sub(hn::GatherIndex(d, vz, nb.j), vzi)));
    });
    dx[i] = ax.total();
    dy[i] = ay.total();
    dz[i] = az.total();
  }
}

void DivergenceSums(const PairInput& in, std::size_t begin, std::size_t end, const real* ux, const real* uy,
                    const real* uz, real* out) {
  const D d;
  const KernelVectors K(in.kernels);
  for (std::size_t i = begin; i < end; ++i) {
    const V uxi = hn::Set(d, ux[i]), uyi = hn::Set(d, uy[i]), uzi = hn::Set(d, uz[i]);
    Sum sum;
    for_neighbor_vectors(in, i, masses(in), in.uniform_mass, [&](std::size_t v, const Neighbors& nb) {
      const V along = hn::Add(hn::Add(hn::Mul(hn::Sub(uxi, hn::GatherIndex(d, ux, nb.j)), nb.dx),
                                      hn::Mul(hn::Sub(uyi, hn::GatherIndex(d, uy, nb.j)), nb.dy)),
                              hn::Mul(hn::Sub(uzi, hn::GatherIndex(d, uz, nb.j)), nb.dz));
      sum.add(v, hn::Mul(hn::Mul(nb.weight, K.grad_factor(nb.r2)), along));
    });
    out[i] = sum.total();
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace pbf
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include <cmath>

#include "engine/distributed/comm.hpp"

namespace pbf {

real uniform_mass(const real* m, std::size_t n, bool across_ranks) {
  real mine = n > 0 && m[0] > 0 ? m[0] : 0;
  for (std::size_t i = 1; i < n && mine > 0; ++i)
    if (m[i] != m[0]) mine = 0;
  if (!across_ranks) return mine;
  // A rank without particles has no say; one whose masses differ makes the answer 0.
  const double lo = comm::min(n ? double(mine) : HUGE_VAL), hi = comm::max(n ? double(mine) : -HUGE_VAL);
  return lo == hi && lo > 0 ? real(lo) : 0;
}

HWY_EXPORT(DensitySums);
HWY_EXPORT(ConstraintSums);
HWY_EXPORT(ConstraintCorrections);
HWY_EXPORT(CurlSums);
HWY_EXPORT(GradientSums);
HWY_EXPORT(SmoothingSums);
HWY_EXPORT(DivergenceSums);

void density_sums(const PairInput& in, std::size_t begin, std::size_t end, real* rho) {
  HWY_DYNAMIC_DISPATCH(DensitySums)(in, begin, end, rho);
}

void constraint_sums(const PairInput& in, std::size_t begin, std::size_t end, real inv_rho0, real* rho, real* grad_x,
                     real* grad_y, real* grad_z, real* grad_sq) {
  HWY_DYNAMIC_DISPATCH(ConstraintSums)(in, begin, end, inv_rho0, rho, grad_x, grad_y, grad_z, grad_sq);
}

void constraint_corrections(const PairInput& in, std::size_t begin, std::size_t end, const real* lambda, real inv_rho0,
                            real scorr_scale, real inv_wdq, int scorr_n, real* dx, real* dy, real* dz) {
  HWY_DYNAMIC_DISPATCH(ConstraintCorrections)
  (in, begin, end, lambda, inv_rho0, scorr_scale, inv_wdq, scorr_n, dx, dy, dz);
}

void curl_sums(const PairInput& in, std::size_t begin, std::size_t end, const real* volume, const real* vx,
               const real* vy, const real* vz, real* wx, real* wy, real* wz, real* magnitude) {
  HWY_DYNAMIC_DISPATCH(CurlSums)(in, begin, end, volume, vx, vy, vz, wx, wy, wz, magnitude);
}

void gradient_sums(const PairInput& in, std::size_t begin, std::size_t end, const real* volume, const real* f, real* ex,
                   real* ey, real* ez) {
  HWY_DYNAMIC_DISPATCH(GradientSums)(in, begin, end, volume, f, ex, ey, ez);
}

void smoothing_sums(const PairInput& in, std::size_t begin, std::size_t end, const real* volume, const real* vx,
                    const real* vy, const real* vz, real* dx, real* dy, real* dz) {
  HWY_DYNAMIC_DISPATCH(SmoothingSums)(in, begin, end, volume, vx, vy, vz, dx, dy, dz);
}

void divergence_sums(const PairInput& in, std::size_t begin, std::size_t end, const real* ux, const real* uy,
                     const real* uz, real* out) {
  HWY_DYNAMIC_DISPATCH(DivergenceSums)(in, begin, end, ux, uy, uz, out);
}

}  // namespace pbf
#endif

#include "engine/geometry/solid_map.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "engine/core/error.hpp"
#include "engine/sph/kernels.hpp"
#include "engine/sph/wall_density.hpp"

namespace pbf {

namespace {

// A brick's centre is at most this far from its nodes.
double brick_reach(int cells_per_brick, double cell) { return 0.5 * std::sqrt(3.0) * cells_per_brick * cell; }

// The centre of sub-cell j of a cell of size c, relative to the cell's centre.
Point sub_offset(int j, double c) {
  constexpr int M = 4;
  return {c * ((j % M + 0.5) / M - 0.5), c * ((j / M % M + 0.5) / M - 0.5), c * ((j / (M * M) + 0.5) / M - 0.5)};
}

// The wall's share of a cell around a node at distance d into the fluid.
double occupancy(double d, double delta, double cell) { return std::clamp(0.5 - (d + delta) / cell, 0.0, 1.0); }

}  // namespace

double SolidMap::required_reach(double h, double cell, double delta) {
  return h + 2 * cell + std::abs(delta) + brick_reach(B, cell);
}

void SolidMap::build(const Shape& shape, bool fluid_inside, const Region& region, const HalfSpaceWall& wall,
                     const Kernels& kernels) {
  const double h = kernels.h, c = region.cell, delta = wall.delta();
  if (shape.reach() < required_reach(h, c, delta))
    throw Error(fmt::format("solid map: the shape's distances reach {} m, {} m are needed", shape.reach(),
                            required_reach(h, c, delta)));
  wall_ = &wall;
  cell_ = c;
  inv_cell_ = real(1 / c);
  // Nodes cover the domain and, beyond it, every node a convolution near the domain reads.
  const double margin = h + 3 * c;
  std::int64_t count = 1;
  for (int a = 0; a < 3; ++a) {
    origin_[a] = c * std::floor((region.lo[a] - margin) / c);
    origin_r_[a] = real(origin_[a]);
    const double cells = std::ceil((region.hi[a] + margin - origin_[a]) / c);
    bricks_[a] = static_cast<std::int64_t>(std::ceil(cells / B));
    count *= bricks_[a];
  }
  if (count > (std::int64_t(1) << 31))
    throw Error(fmt::format("solid map: {} bricks of {} m; the domain is too large for this kernel radius", count,
                            B * c));
  brick_of_.assign(static_cast<std::size_t>(count), kFluid);

  // Which bricks are near the surface: judged at their centres.
  const double sign = fluid_inside ? -1 : 1;
  const double reach = brick_reach(B, c);
  const double below = -(2 * c + std::abs(delta) + reach), above = h + c + std::abs(delta) + reach;
#pragma omp parallel for schedule(dynamic, 64)
  for (std::int64_t b = 0; b < count; ++b) {
    const std::int64_t bx = b % bricks_[0], by = (b / bricks_[0]) % bricks_[1], bz = b / (bricks_[0] * bricks_[1]);
    const Point centre{origin_[0] + (bx + 0.5) * B * c, origin_[1] + (by + 0.5) * B * c,
                       origin_[2] + (bz + 0.5) * B * c};
    const double d = sign * shape.signed_distance(centre);
    brick_of_[b] = d <= below ? kWall : (d >= above ? kFluid : 0);
  }
  active_ = 0;
  corner_.clear();
  for (std::int64_t b = 0; b < count; ++b) {
    if (brick_of_[b] != 0) continue;
    brick_of_[b] = static_cast<std::int32_t>(active_++);
    corner_.push_back(b % bricks_[0] * B);
    corner_.push_back((b / bricks_[0]) % bricks_[1] * B);
    corner_.push_back(b / (bricks_[0] * bricks_[1]) * B);
  }
  computed_.assign(active_ * kNodes, Node{0, 0});

  // Distances at the nodes, and the wall's share of each node's cell: from the distance where
  // the surface is far from the cell; near it, averaged over 4^3 sub-cells, so that the share
  // is right where the surface bends (at an edge a cell is three quarters wall, not half).
  // A shape whose distances are themselves trilinear in a grid of this cell size (a mesh's)
  // is sampled between nodes by trilinear interpolation of the nodes, at no further cost.
  auto node_position = [&](std::size_t k, int n) {
    return Point{origin_[0] + double(corner_[3 * k] + n % N) * c, origin_[1] + double(corner_[3 * k + 1] + n / N % N) * c,
                 origin_[2] + double(corner_[3 * k + 2] + n / (N * N)) * c};
  };
#pragma omp parallel for schedule(dynamic, 4)
  for (std::size_t k = 0; k < active_; ++k)
    for (int n = 0; n < kNodes; ++n) computed_[k * kNodes + n].d = float(sign * shape.signed_distance(node_position(k, n)));
  const bool same_grid = shape.grid_cell() == c;
  auto distance_at = [&](const Point& q) {
    bool near = false;
    const double d = same_grid ? trilinear_distance(q, near) : 0;
    return near ? d : sign * shape.signed_distance(q);
  };
  occupancy_.assign(active_ * kNodes, {0.0f, 0.0f, 0.0f, 0.0f});
#pragma omp parallel for schedule(dynamic, 4)
  for (std::size_t k = 0; k < active_; ++k)
    for (int n = 0; n < kNodes; ++n) {
      const Point p = node_position(k, n);
      const double d = computed_[k * kNodes + n].d;
      auto& share = occupancy_[k * kNodes + n];
      if (std::abs(d + delta) >= c) {
        share[0] = d + delta < 0 ? 1.0f : 0.0f;
        continue;
      }
      double sum[4] = {0, 0, 0, 0};
      for (int sub = 0; sub < kSubCells; ++sub) {
        const Point o = sub_offset(sub, c);
        const double occ = occupancy(distance_at({p[0] + o[0], p[1] + o[1], p[2] + o[2]}), delta, c / kSub);
        sum[0] += occ;
        for (int a = 0; a < 3; ++a) sum[a + 1] += occ * o[a];
      }
      for (int a = 0; a < 4; ++a) share[a] = float(sum[a] / kSubCells);
    }
  std::vector<Tap> taps;
  const double S = make_taps(kernels, taps);
#pragma omp parallel for schedule(dynamic, 4)
  for (std::size_t k = 0; k < active_; ++k) convolve(k, taps, S, h);
  occupancy_ = {};
  // From the node values: the spline's coefficients overshoot them at a thin wall's faces.
  deepest_node_ = -std::numeric_limits<double>::infinity();
  for (const Node& n : computed_) deepest_node_ = std::max(deepest_node_, -double(n.d));
  store_padded(shape, sign);
  computed_ = {};
  mark_far_bricks(h + std::abs(delta));
}

// The spline's coefficients, and each brick's copy of them with the ring of neighbours its
// spline reads. A spline through the node values v would need a global solve; sweeps of
// c <- c + (v - S c) from c = v, with S the spline's own smoothing at the nodes (1/8, 3/4,
// 1/8 along each axis), leave it off by (1 - S)^(sweeps + 1) v: exact on a flat wall
// whatever the count, and at an edge or a corner closer to the node values with each. Two
// sweeps: with one, a lattice's edge particles start 0.57% over rho0 and its corner particles
// 0.85% (with two 0.35% and 0.46%); over-dense, the one-sided solver pushes them, and
// particles of the free surface slid along the walls into the vertical edges at up to 0.08
// m/s (docs/physics.md, "A column at rest"). A node in no brick is far from the surface,
// where F = 0 and d_eff = d.
void SolidMap::store_padded(const Shape& shape, double sign) {
  auto value = [&](const std::int64_t i[3]) {
    if (const Node* own = owned_node(i[0], i[1], i[2])) return *own;
    const float d = float(sign * shape.signed_distance({origin_[0] + double(i[0]) * cell_, origin_[1] + double(i[1]) * cell_,
                                                        origin_[2] + double(i[2]) * cell_}));
    return Node{d, d};
  };
  auto global = [&](std::size_t k, int n, int l, int first, std::int64_t i[3]) {
    for (int a = 0; a < 3; ++a) i[a] = corner_[3 * k + a] + (a == 0 ? n % l : a == 1 ? n / l % l : n / (l * l)) + first;
  };
  constexpr int kSweeps = 2;
  const std::vector<Node> target = computed_;
  std::vector<Node> next(computed_.size());
  for (int sweep = 0; sweep < kSweeps; ++sweep) {
#pragma omp parallel for schedule(dynamic, 4)
    for (std::size_t k = 0; k < active_; ++k)
      for (int n = 0; n < kNodes; ++n) {
        if (n % N == B || n / N % N == B || n / (N * N) == B) continue;  // the next brick's (owned_node)
        std::int64_t i[3];
        global(k, n, N, 0, i);
        double smooth[2] = {0, 0};
        for (int q = 0; q < 27; ++q) {
          const int o[3] = {q % 3 - 1, q / 3 % 3 - 1, q / 9 - 1};
          double w = 1;
          for (int a = 0; a < 3; ++a) w *= o[a] == 0 ? 0.75 : 0.125;
          const std::int64_t j[3] = {i[0] + o[0], i[1] + o[1], i[2] + o[2]};
          const Node c = value(j);
          smooth[0] += w * c.d;
          smooth[1] += w * c.d_eff;
        }
        const Node &c = computed_[k * kNodes + n], &v = target[k * kNodes + n];
        next[k * kNodes + n] = Node{float(c.d + v.d - smooth[0]), float(c.d_eff + v.d_eff - smooth[1])};
      }
    next.swap(computed_);  // owned_node() reads the coefficients of this sweep
  }
  nodes_.assign(active_ * 2 * kPadded, 0.0f);
#pragma omp parallel for schedule(dynamic, 4)
  for (std::size_t k = 0; k < active_; ++k)
    for (int n = 0; n < kPadded; ++n) {
      std::int64_t i[3];
      global(k, n, P, -1, i);
      const Node v = value(i);
      nodes_[k * 2 * kPadded + n] = v.d;
      nodes_[k * 2 * kPadded + kPadded + n] = v.d_eff;
    }
}

// A brick is active where its centre is within about h + 3.5 cells of the surface, so that
// every point within h is in one; most of its points lie farther. Where every coefficient a
// brick stores has d and d_eff at least `far`, the spline (weights >= 0 that sum to 1) is at
// least `far` everywhere in the brick: the wall fraction is 0 and the distance beyond every
// use of it (contact, projection), so the brick answers as far fluid, with one index lookup
// in place of 27 nodes (2026-11-26: the particles 2 to 6 spacings from a wall).
void SolidMap::mark_far_bricks(double far) {
  far_ = far;
  const float threshold = float(far);
  for (std::int32_t& b : brick_of_) {
    if (b < 0) continue;
    const float* v = &nodes_[static_cast<std::size_t>(b) * 2 * kPadded];  // d, then d_eff
    bool beyond = true;
    for (int n = 0; n < 2 * kPadded && beyond; ++n) beyond = v[n] >= threshold;
    if (beyond) b = kFluid;
  }
}

double SolidMap::deepest() const {
  for (std::int32_t b : brick_of_)
    if (b == kWall) return std::numeric_limits<double>::infinity();
  return deepest_node_;
}

const SolidMap::Node* SolidMap::owned_node(std::int64_t ix, std::int64_t iy, std::int64_t iz) const {
  const std::int64_t i[3] = {ix, iy, iz};
  for (int a = 0; a < 3; ++a)
    if (i[a] < 0 || i[a] / B >= bricks_[a]) return nullptr;
  const std::int32_t brick = brick_of_[static_cast<std::size_t>(((iz / B) * bricks_[1] + iy / B) * bricks_[0] + ix / B)];
  if (brick < 0) return nullptr;
  return &computed_[static_cast<std::size_t>(brick) * kNodes +
                    static_cast<std::size_t>(((iz % B) * N + iy % B) * N + ix % B)];
}


// The stencil: W and grad_y W(y - x) = g(r) (y - x) averaged over each cell (8^3 points),
// since W changes much across a cell near the edge of its support. Returns the sum of the
// weights.
double SolidMap::make_taps(const Kernels& kernels, std::vector<Tap>& taps) const {
  const double c = cell_, h = kernels.h, h2 = h * h;
  const int R = static_cast<int>(std::ceil(h / c)) + 1;
  constexpr int Q = 8;
  double S = 0;
  taps.clear();
  for (int z = -R; z <= R; ++z)
    for (int y = -R; y <= R; ++y)
      for (int x = -R; x <= R; ++x) {
        Tap t{{x, y, z}, 0, {0, 0, 0}};
        for (int q = 0; q < Q * Q * Q; ++q) {
          const double o[3] = {c * (x + (q % Q + 0.5) / Q - 0.5), c * (y + (q / Q % Q + 0.5) / Q - 0.5),
                               c * (z + (q / (Q * Q) + 0.5) / Q - 0.5)};
          const double r2 = o[0] * o[0] + o[1] * o[1] + o[2] * o[2];
          if (r2 >= h2) continue;
          t.w += double(kernels.W(real(r2))) / (Q * Q * Q);
          const double g = kernels.grad_factor(real(r2));
          for (int a = 0; a < 3; ++a) t.g[a] += g * o[a] / (Q * Q * Q);
        }
        if (t.w == 0) continue;
        S += t.w;
        taps.push_back(t);
      }
  return S;
}

// The wall fraction F at the nodes of one brick that lie where a particle can feel the wall,
// stored as the distance at which a flat wall gives the same fraction (the header says why).
void SolidMap::convolve(std::size_t brick, const std::vector<Tap>& taps, double S, double h) {
  const double c = cell_, delta = wall_->delta();
  const int R = static_cast<int>(std::ceil(h / c)) + 1;  // a cell reaches half a cell beyond its node
  const int L = N + 2 * R;  // the block of nodes the brick's stencils read
  const std::int64_t* corner = &corner_[3 * brick];
  // The shares of every cell the brick's stencils read; a brick whose block is all fluid or
  // all wall keeps d_eff = d (F is then 0, or f_plane(d) wherever it matters).
  std::vector<std::array<float, 4>> block(static_cast<std::size_t>(L) * L * L);
  // Brick and place in it of each block coordinate along each axis (-1: beyond the map).
  std::vector<std::int64_t> brick_along[3], local_along[3];
  for (int a = 0; a < 3; ++a)
    for (int x = 0; x < L; ++x) {
      const std::int64_t i = corner[a] + x - R;
      const bool inside = i >= 0 && i / B < bricks_[a];
      brick_along[a].push_back(inside ? i / B : -1);
      local_along[a].push_back(inside ? i % B : 0);
    }
  bool mixed = false;
  for (int z = 0; z < L; ++z)
    for (int y = 0; y < L; ++y)
      for (int x = 0; x < L; ++x) {
        auto& b = block[(static_cast<std::size_t>(z) * L + y) * L + x];
        const std::int64_t bx = brick_along[0][x], by = brick_along[1][y], bz = brick_along[2][z];
        const std::int32_t brick =
            bx < 0 || by < 0 || bz < 0 ? kFluid : brick_of_[static_cast<std::size_t>((bz * bricks_[1] + by) * bricks_[0] + bx)];
        if (brick < 0) {
          b = {brick == kWall ? 1.0f : 0.0f, 0, 0, 0};
        } else {
          b = occupancy_[static_cast<std::size_t>(brick) * kNodes +
                         static_cast<std::size_t>((local_along[2][z] * N + local_along[1][y]) * N + local_along[0][x])];
        }
        mixed = mixed || b[0] != block[0][0] || b[0] * (1 - b[0]) != 0;
      }

  for (int n = 0; n < kNodes; ++n) {
    Node& out = computed_[brick * kNodes + n];
    out.d_eff = out.d;
    // Nodes on the brick's upper faces belong to the next brick (copied in store_padded()).
    if (n % N == B || n / N % N == B || n / (N * N) == B) continue;
    if (!mixed || out.d < -2 * c - std::abs(delta) || out.d > h + c + std::abs(delta)) continue;
    const std::size_t centre = (static_cast<std::size_t>(n / (N * N) + R) * L + (n / N % N + R)) * L + (n % N + R);
    // Each cell's share times the kernel, to first order in where the share lies within the
    // cell: occ W(y_k) + m . grad_y W(y_k), with m the share's first moment.
    double F = 0;
    for (const Tap& t : taps) {
      const float* wall = block[centre + static_cast<std::ptrdiff_t>((t.k[2] * L + t.k[1]) * L + t.k[0])].data();
      if (wall[0] == 0) continue;  // a fluid cell (its moment is zero too)
      F += wall[0] * t.w + wall[1] * t.g[0] + wall[2] * t.g[1] + wall[3] * t.g[2];
    }
    F /= S;
    if (F <= 0) continue;  // beyond the wall's reach: d itself continues the field
    // The flat-wall fraction falls monotonically with the distance: bisect for the one that gives F.
    double lo = -h - delta, hi = h - delta;
    for (int it = 0; it < 40; ++it) {
      const double mid = 0.5 * (lo + hi);
      real slope;
      (wall_->fraction_both_sides(real(mid), slope) > F ? lo : hi) = mid;
    }
    out.d_eff = float(0.5 * (lo + hi));
  }
}

std::int32_t SolidMap::brick_at(real x, real y, real z, int cell[3], real t[3]) const {
  const real p[3] = {x, y, z};
  std::int64_t i[3];
  for (int a = 0; a < 3; ++a) {
    const real f = (p[a] - origin_r_[a]) * inv_cell_;
    if (!(f >= 0 && f < real(bricks_[a] * B))) return kFluid;  // beyond the map: beyond the domain
    i[a] = static_cast<std::int64_t>(f);
    t[a] = f - real(i[a]);
    cell[a] = static_cast<int>(i[a] % B);
  }
  return brick_of_[static_cast<std::size_t>(((i[2] / B) * bricks_[1] + i[1] / B) * bricks_[0] + i[0] / B)];
}

double SolidMap::trilinear_distance(const Point& q, bool& near) const {
  int l[3];
  real t[3];
  const std::int32_t brick = brick_at(real(q[0]), real(q[1]), real(q[2]), l, t);
  near = brick >= 0;
  if (!near) return 0;
  const Node* v = &computed_[static_cast<std::size_t>(brick) * kNodes + static_cast<std::size_t>((l[2] * N + l[1]) * N + l[0])];
  double value = 0;
  for (int corner = 0; corner < 8; ++corner) {
    const int o[3] = {corner & 1, (corner >> 1) & 1, corner >> 2};
    double w = 1;
    for (int a = 0; a < 3; ++a) w *= o[a] ? double(t[a]) : 1 - double(t[a]);
    value += w * v[(o[2] * N + o[1]) * N + o[0]].d;
  }
  return value;
}

// The quadratic B-spline (header) of one member of the nodes, and its gradient where `grad`
// is not null: per axis the weights of the nearest node's neighbours below, itself and above,
// at u from it (|u| <= 1/2), then sums along x, y, z in turn.
template <bool kGradient>
void SolidMap::spline(const float* v, const int cell[3], const real t[3], real& value, real grad[3]) const {
  real w[3][3], dw[3][3];
  int first[3];
  for (int a = 0; a < 3; ++a) {
    const bool upper = t[a] >= real(0.5);
    const real u = upper ? t[a] - 1 : t[a];
    first[a] = cell[a] + (upper ? 1 : 0);  // the node below the nearest, stored one place up
    const real below = real(0.5) - u, above = real(0.5) + u;
    w[a][0] = real(0.5) * below * below;
    w[a][1] = real(0.75) - u * u;
    w[a][2] = real(0.5) * above * above;
    dw[a][0] = -below;
    dw[a][1] = -2 * u;
    dw[a][2] = above;
  }
  const float* o = v + static_cast<std::size_t>((first[2] * P + first[1]) * P + first[0]);
  real sum = 0, gx = 0, gy = 0, gz = 0;
  for (int c = 0; c < 3; ++c) {
    real s = 0, sy = 0, sx = 0;  // over y: the x sums, their y derivative, the x derivatives
    for (int b = 0; b < 3; ++b) {
      const float* row = o + static_cast<std::size_t>((c * P + b) * P);
      const real r0 = row[0], r1 = row[1], r2 = row[2];
      const real along = w[0][0] * r0 + w[0][1] * r1 + w[0][2] * r2;
      s += w[1][b] * along;
      if constexpr (kGradient) {
        sy += dw[1][b] * along;
        sx += w[1][b] * (dw[0][0] * r0 + dw[0][1] * r1 + dw[0][2] * r2);
      }
    }
    sum += w[2][c] * s;
    if constexpr (kGradient) {
      gz += dw[2][c] * s;
      gy += w[2][c] * sy;
      gx += w[2][c] * sx;
    }
  }
  value = sum;
  if constexpr (kGradient) {
    grad[0] = gx * inv_cell_;
    grad[1] = gy * inv_cell_;
    grad[2] = gz * inv_cell_;
  }
}

SolidMap::Where SolidMap::distance(real x, real y, real z, real& d, real grad[3]) const {
  int cell[3];
  real t[3];
  const std::int32_t brick = brick_at(x, y, z, cell, t);
  if (brick < 0) return brick == kFluid ? Where::fluid : Where::wall;
  const float* first = &nodes_[static_cast<std::size_t>(brick) * 2 * kPadded];
  if (grad)
    spline<true>(first, cell, t, d, grad);
  else
    spline<false>(first, cell, t, d, grad);
  return Where::near;
}

SolidMap::Where SolidMap::fraction(real x, real y, real z, real& f, real grad[3]) const {
  int cell[3];
  real t[3];
  const std::int32_t brick = brick_at(x, y, z, cell, t);
  if (brick < 0) {
    f = brick == kFluid ? 0 : 1;
    grad[0] = grad[1] = grad[2] = 0;
    return brick == kFluid ? Where::fluid : Where::wall;
  }
  real d_eff, slope;
  spline<true>(&nodes_[static_cast<std::size_t>(brick) * 2 * kPadded + kPadded], cell, t, d_eff, grad);
  f = wall_->fraction_both_sides(d_eff, slope);
  for (int a = 0; a < 3; ++a) grad[a] *= slope;
  return Where::near;
}

SolidMap::Where SolidMap::effective_distance(real x, real y, real z, real& d_eff, real grad[3]) const {
  int cell[3];
  real t[3];
  const std::int32_t brick = brick_at(x, y, z, cell, t);
  if (brick < 0) return brick == kFluid ? Where::fluid : Where::wall;
  spline<true>(&nodes_[static_cast<std::size_t>(brick) * 2 * kPadded + kPadded], cell, t, d_eff, grad);
  return Where::near;
}

}  // namespace pbf

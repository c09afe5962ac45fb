#pragma once
// What a solid does to the fluid near it, precomputed once on a sparse grid around its
// surface (a density map in the sense of Koschier & Bender 2017):
//   d(x)   the distance into the fluid (negative inside the wall), for projection and contact;
//   f(x)   the fraction of a full neighbourhood the wall fills, the wall's density over rho0:
//          F(x) = sum_k occ(y_k) W(x - y_k) / sum_k W(x - y_k)
//          over the cells y_k within h of x, where occ is the wall's share of a cell (the wall
//          counts as fluid from delta behind its surface, engine/sph/wall_density.hpp),
//          averaged over 4^3 sub-cells where the cell straddles the surface and used to first
//          order in where it lies within the cell, and W is averaged over each cell.
// F is stored as the distance d_eff at which a flat wall gives it, f = f_plane(d_eff): on a
// flat wall d_eff = d, a linear function (so the map gives the analytic box there), and at
// edges, corners and curves d_eff stays smooth where F itself, an eighth-degree polynomial
// of the distance, would not interpolate well. grad f = f_plane'(d_eff) grad d_eff.
//
// Between nodes both are a quadratic B-spline of coefficients c_k at the nodes (k = index):
//   v(x) = sum_k B(x/c - k) c_k,  B the product over the axes of
//   b(u) = 3/4 - u^2 (|u| <= 1/2),  (3/2 - |u|)^2 / 2 (1/2 <= |u| <= 3/2),  0 beyond,
// 27 nodes around the nearest one. It reproduces linear functions exactly (a flat wall stays
// exact) and its gradient is continuous. Trilinear interpolation's is not: at an edge or a
// corner, where d has a kink and d_eff bends within a cell, its gradient jumps by half its
// size at every node plane, and the first layer of a column at rest sits on those planes
// (half a spacing from the walls, nodes half a spacing apart); the wall's force and the
// projection's normal flipped as particles crossed them, kicking corner particles to 0.1 m/s.
// A B-spline smooths (its value at a node is 3/4 of the node's coefficient and 1/8 of each
// neighbour's along each axis): c_k = v_k would round edges and corners by too much, so two
// sweeps bring the spline close to the node values v_k (store_padded).
// The price: a kink is still rounded over about a cell, and a lookup reads 27 nodes, not 8.
//
// Storage: bricks of 4^3 cells only where |d| < h + a brick's reach; each holds its 4^3
// nodes and a copy of the ring of neighbours the spline reads (7^3 nodes), so a lookup stays
// within one brick. The other bricks know only which side they are on: a query far from the
// wall costs one index lookup.
#include <array>
#include <cstdint>
#include <vector>

#include "engine/core/real.hpp"
#include "engine/geometry/shape.hpp"

namespace pbf {

class HalfSpaceWall;
struct Kernels;

class SolidMap {
 public:
  struct Region {
    Point lo, hi;     // where fluid may be (the domain)
    double cell = 0;  // node spacing
  };
  // `fluid_inside`: a container (the fluid is on the shape's inside).
  // `wall` must outlive the map (its flat-wall formula is evaluated at every query). Needs
  // shape.reach() >= required_reach(kernels.h, region.cell, wall.delta()).
  void build(const Shape& shape, bool fluid_inside, const Region& region, const HalfSpaceWall& wall,
             const Kernels& kernels);
  static double required_reach(double h, double cell, double delta);

  enum class Where { fluid, near, wall };  // far in the fluid, near the surface, deep in the wall

  // d and grad d at a point (grad d is the unit normal into the fluid near the surface); d
  // alone, at about half the cost, where `grad` is null.
  Where distance(real x, real y, real z, real& d, real grad[3]) const;
  // The wall fraction f with its gradient (f = 0 far in the fluid).
  Where fraction(real x, real y, real z, real& f, real grad[3]) const;
  // d_eff, the distance at which a flat wall fills the fraction f, with its gradient (about
  // the unit normal into the fluid); left alone far in the fluid and deep in the wall.
  Where effective_distance(real x, real y, real z, real& d_eff, real grad[3]) const;

  // A distance every point answered as Where::fluid is at least (h + |delta|).
  double far_distance() const { return far_; }

  // How deep the wall's deepest node lies (-d; infinite when some brick is all wall).
  double deepest() const;

  std::size_t active_bricks() const { return active_; }
  std::size_t total_bricks() const { return brick_of_.size(); }

 private:
  // A brick's cells, the nodes the build computes (its own and its upper faces), and the
  // nodes it stores (one more on each side: from node -1 to node B + 1 along each axis).
  static constexpr int B = 4, N = B + 1, kNodes = N * N * N, P = B + 3, kPadded = P * P * P;
  static constexpr int kSub = 4, kSubCells = kSub * kSub * kSub;  // where a cell straddles the surface
  struct Node {  // single precision whatever `real` is: the map's own error is larger
    float d, d_eff;
  };
  static constexpr std::int32_t kFluid = -1, kWall = -2;

  // The brick holding the cell at (x, y, z), or a far code; the cell's place in the brick and
  // the point's in the cell (0 <= t < 1).
  std::int32_t brick_at(real x, real y, real z, int cell[3], real t[3]) const;
  // The spline of one member of the nodes around a point (`v`: that member of the brick's
  // first stored node), and its gradient if asked.
  template <bool kGradient>
  void spline(const float* v, const int cell[3], const real t[3], real& value, real grad[3]) const;
  // While building: d trilinear between the computed nodes, as a mesh's grid gives it.
  double trilinear_distance(const Point& q, bool& near) const;
  // The spline's coefficients from the computed nodes, into each brick with its ring.
  void store_padded(const Shape& shape, double sign);
  // After building: bricks whose stored coefficients all reach `far` answer as far fluid.
  void mark_far_bricks(double far);
  // While building: node (ix, iy, iz) of the brick that owns it (nullptr where none does).
  const Node* owned_node(std::int64_t ix, std::int64_t iy, std::int64_t iz) const;
  struct Tap {  // a cell of the stencil: its offset, W and grad_y W averaged over it
    int k[3];
    double w, g[3];
  };
  double make_taps(const Kernels& kernels, std::vector<Tap>& taps) const;
  void convolve(std::size_t brick, const std::vector<Tap>& taps, double S, double h);

  double origin_[3] = {0, 0, 0}, cell_ = 1;
  real inv_cell_ = 1, origin_r_[3] = {0, 0, 0};
  std::int64_t bricks_[3] = {0, 0, 0};
  std::vector<std::int32_t> brick_of_;
  // Per active brick, the spline's coefficients of d for its kPadded nodes, then those of
  // d_eff: a lookup reads one member, so each is contiguous (fewer cache lines per row).
  std::vector<float> nodes_;
  std::vector<Node> computed_;  // while building: kNodes per active brick
  // Per node, while building: the wall's share of the node's cell and its first moment.
  std::vector<std::array<float, 4>> occupancy_;
  std::vector<std::int64_t> corner_;  // first cell of each active brick, 3 per brick
  std::size_t active_ = 0;
  double deepest_node_ = 0;  // the largest -d over the nodes
  double far_ = 0;           // see far_distance()
  const HalfSpaceWall* wall_ = nullptr;
};

}  // namespace pbf

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
// flat wall d_eff = d, a linear function that trilinear interpolation reproduces exactly (so
// the map gives the analytic box there), and at edges, corners and curves d_eff stays smooth
// where F itself, an eighth-degree polynomial of the distance, would not interpolate well.
// grad f = f_plane'(d_eff) grad d_eff.
//
// Storage: bricks of 4^3 cells (5^3 nodes) only where |d| < h + a brick's reach; the others
// know only which side they are on. A query far from the wall costs one index lookup.
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

  // d and grad d at a point (grad d is the unit normal into the fluid near the surface).
  Where distance(real x, real y, real z, real& d, real grad[3]) const;
  // The wall fraction f with its gradient (f = 0 far in the fluid).
  Where fraction(real x, real y, real z, real& f, real grad[3]) const;

  // How deep the wall's deepest node lies (-d; infinite when some brick is all wall).
  double deepest() const;

  std::size_t active_bricks() const { return active_; }
  std::size_t total_bricks() const { return brick_of_.size(); }

 private:
  static constexpr int B = 4, N = B + 1, kNodes = N * N * N;
  static constexpr int kSub = 4, kSubCells = kSub * kSub * kSub;  // where a cell straddles the surface
  struct Node {  // single precision whatever `real` is: the map's own error is larger
    float d, d_eff;
  };
  static constexpr std::int32_t kFluid = -1, kWall = -2;

  // The brick holding cell (ix, iy, iz), or a far code; sets the cell's node offset.
  void interpolate(const float* first, const real t[3], real& value, real grad[3]) const;
  std::int32_t brick_at(real x, real y, real z, std::size_t& base, real t[3]) const;
  // d_eff of node (ix, iy, iz) from the brick that owns it (`fallback` where none does).
  double owned_d_eff(std::int64_t ix, std::int64_t iy, std::int64_t iz, double fallback) const;
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
  std::vector<Node> nodes_;  // kNodes per active brick
  // Per node, while building: the wall's share of the node's cell and its first moment.
  std::vector<std::array<float, 4>> occupancy_;
  std::vector<std::int64_t> corner_;  // first cell of each active brick, 3 per brick
  std::size_t active_ = 0;
  const HalfSpaceWall* wall_ = nullptr;
};

}  // namespace pbf

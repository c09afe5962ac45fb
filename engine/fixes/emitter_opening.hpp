#pragma once
// The opening of an emitter (engine/fixes/emitter.cpp): a rectangle (sides a along u, b
// along v) or a disc (radius r) centred at c in the plane normal to n, and the sites where
// its particles enter, as offsets (a, b) from the centre along u and v. For a rectangle the
// na x nb sites are the centres of na x nb equal cells of it, na = round(a/s), nb = round(b/s);
// for a disc they are the N = round(pi r^2 / s^2) sites of the square lattice of spacing s
// nearest its centre (nearer first, then by row and column).
//
// A point over the opening is over the cell of one site: the cells tile the plane around the
// opening (the rectangle's cells, or the disc's lattice cells s x s), a point beyond the last
// cell counting as in it. `nearest_site` answers with that cell's site, or, where the cell
// has no site that is open (one inside a solid, or a cell of the disc's corners), with the
// open site nearest the cell's centre: the site whose value stands for the point.
#include <array>
#include <cstddef>
#include <vector>

#include "engine/registry/params.hpp"

namespace pbf {

class Opening {
 public:
  // Reads shape, center, normal, size or radius, and axis, and checks them together.
  explicit Opening(const Params& p);

  // Lays out the sites for the spacing s (all open); refuses an opening narrower than s.
  void lay_out(double s);
  // Closes the sites with closed[k] set (inside a solid) and finds each cell's site.
  void close(const std::vector<char>& closed);

  std::size_t sites() const { return sites_.size(); }
  bool open(std::size_t k) const { return open_[k] != 0; }
  double area() const;
  const Vec3& center() const { return center_; }
  const Vec3& normal() const { return n_; }
  bool disc() const { return disc_; }
  // The point of site k `ahead` in front of the opening's plane (`site` {0, 0}: the centre).
  Vec3 point(const std::array<double, 2>& site, double ahead) const;
  Vec3 point(std::size_t k, double ahead) const { return point(sites_[k], ahead); }
  // The offset of x from the centre: along u, along v, along n.
  std::array<double, 3> offset(const Vec3& x) const;
  // Whether in-plane offsets (a, b) lie over the opening, widened by `margin`.
  bool over(double a, double b, double margin) const;
  // The open site that stands for in-plane offsets (a, b) (see above).
  std::size_t nearest_site(double a, double b) const { return cell_site_[cell_of(a, b)]; }

 private:
  bool disc_;
  Vec3 center_, n_{}, u_{}, v_{};
  Vec2 size_{0, 0};
  double radius_ = 0;
  std::vector<std::array<double, 2>> sites_;
  std::vector<char> open_;
  // The cells: count_[0] x count_[1] of cell_[0] x cell_[1] from lo_ (in-plane), and the site
  // each stands for.
  std::array<double, 2> lo_{0, 0}, cell_{0, 0};
  std::array<long, 2> count_{0, 0};
  std::vector<std::size_t> cell_site_;
  std::size_t cell_of(double a, double b) const;  // (clamped to the cells)
};

}  // namespace pbf

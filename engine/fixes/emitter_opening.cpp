#include "engine/fixes/emitter_opening.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "engine/core/error.hpp"

namespace pbf {

namespace {

double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 scaled(const Vec3& a, double k) { return {a[0] * k, a[1] * k, a[2] * k}; }
Vec3 unit(const Vec3& a) { return scaled(a, 1 / std::sqrt(dot(a, a))); }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

}  // namespace

Opening::Opening(const Params& p) : disc_(p.string("shape") == "disc"), center_(p.vec3("center")) {
  const Vec3 normal = p.vec3("normal");
  if (!(dot(normal, normal) > 0)) throw Error("parameter 'normal' is the zero vector: the opening needs a direction");
  n_ = unit(normal);
  if (disc_ != p.has("radius") || disc_ == p.has("size"))
    throw Error(disc_ ? "a disc opening takes 'radius' (not 'size')" : "a rectangle opening takes 'size' {a, b} (not 'radius')");
  if (disc_) {
    radius_ = p.real("radius");
  } else {
    size_ = p.vec2("size");
  }
  // The opening's axes: u along `axis` (or the coordinate axis the normal leans on least), v = n x u.
  Vec3 axis = p.has("axis") ? p.vec3("axis") : Vec3{0, 0, 0};
  if (!p.has("axis")) {
    int least = 0;
    for (int a = 1; a < 3; ++a)
      if (std::fabs(n_[a]) < std::fabs(n_[least])) least = a;
    axis[least] = 1;
  }
  const Vec3 along = {axis[0] - dot(axis, n_) * n_[0], axis[1] - dot(axis, n_) * n_[1], axis[2] - dot(axis, n_) * n_[2]};
  if (!(dot(along, along) > 1e-12 * dot(axis, axis)))
    throw Error("parameter 'axis' is along the normal: it must give a direction in the opening's plane");
  u_ = unit(along);
  v_ = cross(n_, u_);
}

double Opening::area() const { return disc_ ? M_PI * radius_ * radius_ : size_[0] * size_[1]; }

void Opening::lay_out(double s) {
  if (disc_ ? 2 * radius_ < s : (size_[0] < s || size_[1] < s))
    throw Error(fmt::format("parameter '{}': the opening is narrower than one particle spacing ({} m)",
                            disc_ ? "radius" : "size", s));
  sites_.clear();
  if (disc_) {  // the lattice sites nearest the centre, nearer first, then by row and column
    const long half = static_cast<long>(std::ceil(radius_ / s)) + 1;
    std::vector<std::array<double, 3>> candidates;  // (squared distance, a, b)
    for (long j = -half; j <= half; ++j)
      for (long i = -half; i <= half; ++i) {
        const double a = double(i) * s, b = double(j) * s;
        candidates.push_back({a * a + b * b, a, b});
      }
    std::stable_sort(candidates.begin(), candidates.end(), [](const auto& x, const auto& y) { return x[0] < y[0]; });
    const auto count = static_cast<std::size_t>(std::max(1.0, std::round(M_PI * radius_ * radius_ / (s * s))));
    for (std::size_t k = 0; k < count; ++k) sites_.push_back({candidates[k][1], candidates[k][2]});
    lo_ = {-(double(half) + 0.5) * s, -(double(half) + 0.5) * s};
    cell_ = {s, s};
    count_ = {2 * half + 1, 2 * half + 1};
  } else {
    const long na = std::lround(size_[0] / s), nb = std::lround(size_[1] / s);
    const double da = size_[0] / double(na), db = size_[1] / double(nb);
    for (long j = 0; j < nb; ++j)
      for (long i = 0; i < na; ++i)
        sites_.push_back({(double(i) + 0.5 - 0.5 * double(na)) * da, (double(j) + 0.5 - 0.5 * double(nb)) * db});
    lo_ = {-0.5 * size_[0], -0.5 * size_[1]};
    cell_ = {da, db};
    count_ = {na, nb};
  }
  close(std::vector<char>(sites_.size(), 0));
}

void Opening::close(const std::vector<char>& closed) {
  open_.assign(sites_.size(), 1);
  for (std::size_t k = 0; k < sites_.size(); ++k) open_[k] = closed[k] ? 0 : 1;
  // Each open site stands for its own cell (it lies at the cell's centre)...
  const auto cells = static_cast<std::size_t>(count_[0] * count_[1]);
  const std::size_t none = std::numeric_limits<std::size_t>::max();
  cell_site_.assign(cells, none);
  for (std::size_t k = 0; k < sites_.size(); ++k)
    if (open_[k]) cell_site_[cell_of(sites_[k][0], sites_[k][1])] = k;
  // ... and a cell without one takes the open site nearest its centre (the first of equals).
  for (std::size_t c = 0; c < cells; ++c) {
    if (cell_site_[c] != none) continue;
    const double a = lo_[0] + (double(c % std::size_t(count_[0])) + 0.5) * cell_[0];
    const double b = lo_[1] + (double(c / std::size_t(count_[0])) + 0.5) * cell_[1];
    double best = std::numeric_limits<double>::infinity();
    std::size_t site = 0;
    for (std::size_t k = 0; k < sites_.size(); ++k) {
      const double d2 = (sites_[k][0] - a) * (sites_[k][0] - a) + (sites_[k][1] - b) * (sites_[k][1] - b);
      if (open_[k] && d2 < best) {
        best = d2;
        site = k;
      }
    }
    cell_site_[c] = site;
  }
}

Vec3 Opening::point(const std::array<double, 2>& site, double ahead) const {
  Vec3 q;
  for (int a = 0; a < 3; ++a) q[a] = center_[a] + site[0] * u_[a] + site[1] * v_[a] + ahead * n_[a];
  return q;
}

std::array<double, 3> Opening::offset(const Vec3& x) const {
  const Vec3 d = {x[0] - center_[0], x[1] - center_[1], x[2] - center_[2]};
  return {dot(d, u_), dot(d, v_), dot(d, n_)};
}

bool Opening::over(double a, double b, double margin) const {
  if (disc_) return a * a + b * b < (radius_ + margin) * (radius_ + margin);
  return std::fabs(a) < 0.5 * size_[0] + margin && std::fabs(b) < 0.5 * size_[1] + margin;
}

std::size_t Opening::cell_of(double a, double b) const {
  const auto i = static_cast<std::size_t>(std::clamp(std::floor((a - lo_[0]) / cell_[0]), 0.0, double(count_[0] - 1)));
  const auto j = static_cast<std::size_t>(std::clamp(std::floor((b - lo_[1]) / cell_[1]), 0.0, double(count_[1] - 1)));
  return j * static_cast<std::size_t>(count_[0]) + i;
}

}  // namespace pbf

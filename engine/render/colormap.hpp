#pragma once
// Colour maps for rendered images: a scalar in [0, 1] to an sRGB colour. The maps are
// matplotlib's (viridis and coolwarm sampled at 33 evenly spaced stops and interpolated
// linearly, within 4 levels of 255 of the originals; jet from its piecewise-linear
// definition; gray), precomputed into a lookup table so that a lookup is one index.
#include <array>
#include <string>
#include <vector>

namespace pbf {

using Rgb = std::array<unsigned char, 3>;

class Colormap {
 public:
  // Throws pbf::Error listing the valid names when `name` is not one of names().
  explicit Colormap(const std::string& name);

  // The colour at t; t is clamped to [0, 1], NaN gives nan_colour().
  Rgb operator()(double t) const;
  // The colour of value v on the scale [vmin, vmax] (vmin < vmax), clamped at both ends.
  Rgb at(double v, double vmin, double vmax) const { return (*this)((v - vmin) / (vmax - vmin)); }

  const std::string& name() const { return name_; }
  static const std::vector<std::string>& names();
  // Neutral grey for values that are not numbers: not at either end of any of the maps.
  static constexpr Rgb nan_colour() { return {150, 150, 150}; }

 private:
  static constexpr int kTableSize = 1024;  // steps of 1/1023: finer than 8-bit output resolves
  std::string name_;
  std::vector<Rgb> table_;
};

// The values to label on a colour bar over [vmin, vmax] (vmin < vmax): 3 to 5 round numbers
// (multiples of 1, 2, 2.5 or 5 times a power of ten) inside the range, or when no such step
// gives at least three, five evenly spaced values from vmin to vmax.
std::vector<double> colorbar_ticks(double vmin, double vmax);

}  // namespace pbf

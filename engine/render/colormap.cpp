#include "engine/render/colormap.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>

#include "engine/core/error.hpp"

namespace pbf {

namespace {

// matplotlib's maps sampled at t = k / 32, k = 0..32 (rounded to 8 bits).
constexpr Rgb kViridis[33] = {
    {68, 1, 84},    {71, 13, 96},   {72, 24, 106},  {72, 35, 116},  {71, 45, 123},  {69, 55, 129},  {66, 64, 134},
    {62, 73, 137},  {59, 82, 139},  {55, 91, 141},  {51, 99, 141},  {47, 107, 142}, {44, 114, 142}, {41, 122, 142},
    {38, 130, 142}, {35, 137, 142}, {33, 145, 140}, {31, 152, 139}, {31, 160, 136}, {34, 167, 133}, {40, 174, 128},
    {50, 182, 122}, {63, 188, 115}, {78, 195, 107}, {94, 201, 98},  {112, 207, 87}, {132, 212, 75}, {152, 216, 62},
    {173, 220, 48}, {194, 223, 35}, {216, 226, 25}, {236, 229, 27}, {253, 231, 37},
};
constexpr Rgb kCoolwarm[33] = {
    {59, 76, 192},   {68, 90, 204},   {78, 104, 216},  {88, 117, 225},  {98, 130, 234},  {108, 143, 241},
    {119, 154, 247}, {130, 166, 251}, {141, 176, 254}, {152, 185, 255}, {163, 194, 254}, {174, 201, 252},
    {185, 208, 249}, {195, 213, 244}, {204, 217, 237}, {213, 219, 229}, {221, 220, 220}, {229, 216, 209},
    {236, 211, 197}, {241, 204, 184}, {245, 196, 172}, {247, 186, 159}, {247, 176, 147}, {246, 165, 134},
    {244, 152, 122}, {240, 139, 110}, {235, 125, 98},  {228, 110, 86},  {221, 95, 75},   {212, 78, 65},
    {202, 59, 55},   {190, 36, 46},   {180, 4, 38},
};

// Linear interpolation between evenly spaced stops.
std::array<double, 3> from_stops(std::span<const Rgb> stops, double t) {
  const double position = t * static_cast<double>(stops.size() - 1);
  const std::size_t k = std::min(static_cast<std::size_t>(position), stops.size() - 2);
  const double w = position - static_cast<double>(k);
  std::array<double, 3> c;
  for (int ch = 0; ch < 3; ++ch) c[ch] = (1 - w) * stops[k][ch] + w * stops[k + 1][ch];
  return c;
}

// A piecewise-linear channel through the points (t, value), t ascending from 0 to 1.
double piecewise(std::initializer_list<std::array<double, 2>> points, double t) {
  const std::array<double, 2>* previous = points.begin();
  for (const auto& p : points) {
    if (t <= p[0]) {
      if (p[0] == (*previous)[0]) return p[1];
      const double w = (t - (*previous)[0]) / (p[0] - (*previous)[0]);
      return (1 - w) * (*previous)[1] + w * p[1];
    }
    previous = &p;
  }
  return (*previous)[1];
}

// matplotlib's jet, from its segment data.
std::array<double, 3> jet(double t) {
  const double r = piecewise({{0, 0}, {0.35, 0}, {0.66, 1}, {0.89, 1}, {1, 0.5}}, t);
  const double g = piecewise({{0, 0}, {0.125, 0}, {0.375, 1}, {0.64, 1}, {0.91, 0}, {1, 0}}, t);
  const double b = piecewise({{0, 0.5}, {0.11, 1}, {0.34, 1}, {0.65, 0}, {1, 0}}, t);
  return {255 * r, 255 * g, 255 * b};
}

}  // namespace

const std::vector<std::string>& Colormap::names() {
  static const std::vector<std::string> all = {"viridis", "coolwarm", "jet", "gray"};
  return all;
}

Colormap::Colormap(const std::string& name) : name_(name), table_(kTableSize) {
  const auto& valid = names();
  if (std::find(valid.begin(), valid.end(), name) == valid.end()) {
    std::string list;
    for (const auto& v : valid) list += (list.empty() ? "" : ", ") + v;
    throw Error("unknown colour map '" + name + "' (valid: " + list + ")");
  }
  for (int k = 0; k < kTableSize; ++k) {
    const double t = static_cast<double>(k) / (kTableSize - 1);
    std::array<double, 3> c;
    if (name == "viridis")
      c = from_stops(kViridis, t);
    else if (name == "coolwarm")
      c = from_stops(kCoolwarm, t);
    else if (name == "jet")
      c = jet(t);
    else
      c = {255 * t, 255 * t, 255 * t};
    for (int ch = 0; ch < 3; ++ch)
      table_[k][ch] = static_cast<unsigned char>(std::lround(std::clamp(c[ch], 0.0, 255.0)));
  }
}

Rgb Colormap::operator()(double t) const {
  if (std::isnan(t)) return nan_colour();
  const double clamped = std::clamp(t, 0.0, 1.0);
  return table_[static_cast<std::size_t>(std::lround(clamped * (kTableSize - 1)))];
}

std::vector<double> colorbar_ticks(double vmin, double vmax) {
  const double range = vmax - vmin, decade = std::pow(10.0, std::floor(std::log10(range / 4)));
  std::vector<double> values;
  for (double mantissa : {1.0, 2.0, 2.5, 5.0, 10.0}) {
    const double step = mantissa * decade;
    // Tolerances of 1e-9 steps, so that a range end a rounding away from a multiple counts.
    const double k0 = std::ceil(vmin / step - 1e-9), count = std::floor(vmax / step + 1e-9) - k0 + 1;
    if (count > 5) continue;
    if (count >= 3 && std::fabs(k0) < 1e15)  // k0 + j exact in double
      for (int j = 0; j < count; ++j) values.push_back((k0 + j) * step);
    break;
  }
  if (values.empty())
    for (int k = 0; k <= 4; ++k) values.push_back(vmin + range * k / 4);
  return values;
}

}  // namespace pbf

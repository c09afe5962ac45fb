#include "engine/sph/compression_watch.hpp"

#include <cmath>
#include <fmt/format.h>

namespace pbf {

namespace {

// Two significant digits, rounded down: a suggestion on the safe side.
double two_digits_down(double x) {
  if (!(x > 0)) return x;
  const double unit = std::pow(10.0, std::floor(std::log10(x)) - 1);
  return std::floor(x / unit) * unit;
}

std::string staying_above(const std::string& fix, double mean, std::int64_t step) {
  return fmt::format("{}: the fluid's mean compression has stayed above {:g}% for {} steps ({:.3g}% at step {})",
                     fix, 100 * CompressionWatch::kLevel, CompressionWatch::kSteps, 100 * mean, step);
}

}  // namespace

std::string pbf_compression_warning(const std::string& fix, double mean, std::int64_t step, double dt, double h,
                                    int iterations) {
  return fmt::format("{}: the time step {} s is too large for the kernel radius {} m with {} iterations; about {} s "
                     "would keep it near 1%, or more iterations, or fix 'cfl' with 'iterations' to choose the step "
                     "(docs/user-guide.md#choosing-the-time-step)",
                     staying_above(fix, mean, step), dt, h, iterations, two_digits_down(dt * std::sqrt(0.01 / mean)));
}

std::string wcsph_compression_warning(const std::string& fix, double mean, std::int64_t step, double c0, double speed,
                                      double h) {
  const double c0_wanted = std::max(10 * speed, c0 * std::sqrt(mean / 0.01));
  return fmt::format("{}: the sound speed {:.4g} m/s is too low for this flow ({:.3g} m/s at most); about 'sound_speed "
                     "= {:.3g}' would keep it near 1%, with a step of at most 0.15 h / c0 = {:.3g} s (fix 'cfl' "
                     "chooses it) (docs/user-guide.md#choosing-the-time-step)",
                     staying_above(fix, mean, step), c0, speed, c0_wanted, 0.15 * h / c0_wanted);
}

}  // namespace pbf

#include "engine/sph/resolution.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <spdlog/spdlog.h>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/distributed/comm.hpp"

namespace pbf {

double sampled_spacing(const real* x, const real* y, const real* z, std::size_t n) {
  if (n < 2) return 0;
  const std::size_t samples = std::min<std::size_t>(n, 256);
  std::vector<double> nearest(samples);
#pragma omp parallel for schedule(static)
  for (std::size_t s = 0; s < samples; ++s) {
    const std::size_t i = s * n / samples;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < n; ++j) {
      const double dx = double(x[i]) - x[j], dy = double(y[i]) - y[j], dz = double(z[i]) - z[j];
      const double r2 = dx * dx + dy * dy + dz * dz;
      if (j != i && r2 < best) best = r2;
    }
    nearest[s] = std::sqrt(best);
  }
  std::nth_element(nearest.begin(), nearest.begin() + static_cast<std::ptrdiff_t>(samples / 2), nearest.end());
  return nearest[samples / 2];
}

double sampled_spacing_of_shares(const real* x, const real* y, const real* z, std::size_t n, bool distributed) {
  const double spacing = sampled_spacing(x, y, z, n);
  if (!distributed) return spacing;
  const double least = comm::min(spacing > 0 ? spacing : HUGE_VAL);
  return std::isfinite(least) ? least : 0;
}

void check_kernel_radius(double h, double spacing, const std::string& what) {
  if (!(spacing > 0)) return;  // a single particle, or all in one place: nothing to compare
  const double ratio = h / spacing;
  const std::string situation =
      fmt::format("{}: the kernel radius h = {:.4g} m is {:.3g} particle spacings (spacing {:.4g} m)", what, h, ratio,
                  spacing);
  if (ratio < kMinSpacings)
    throw Error(fmt::format("{}; below one spacing a particle has no neighbours: set pbf.kernel_radius to about 2 "
                            "spacings ({:.4g} m)",
                            situation, 2 * spacing));
  if (ratio > kMaxSpacings)
    throw Error(fmt::format("{}; above {} spacings each particle has thousands of neighbours for no accuracy gained: "
                            "set pbf.kernel_radius to about 2 spacings ({:.4g} m)",
                            situation, kMaxSpacings, 2 * spacing));
  if (ratio < kUsualMinSpacings || ratio > kUsualMaxSpacings)
    spdlog::warn("{}; the solvers are meant for {} to {} (2 is usual)", situation, kUsualMinSpacings,
                 kUsualMaxSpacings);
}

}  // namespace pbf

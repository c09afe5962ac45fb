#pragma once
// A solver whose fluid stays compressed: PBF's step too large for its spacing and iterations,
// WCSPH's sound speed too low for its flow. Neither blows up; the fluid is quietly wrong (21%
// denser than water, where a user expects about 1%). The solver reports its mean compression,
// mean of max(rho/rho0 - 1, 0); this says once when it stays above kLevel for kSteps steps.
#include <cstdint>
#include <string>

namespace pbf {

class CompressionWatch {
 public:
  static constexpr double kLevel = 0.03;  // 3%: PBF's accuracy targets are 0.1 to 1%, WCSPH's 1%
  static constexpr std::int64_t kSteps = 50;

  // After a measurement `steps` steps after the last one: whether the warning is due now.
  bool due(double mean_compression, std::int64_t steps = 1) {
    if (warned_) return false;
    above_ = mean_compression > kLevel ? above_ + steps : 0;
    warned_ = above_ >= kSteps;
    return warned_;
  }

 private:
  std::int64_t above_ = 0;
  bool warned_ = false;
};

// The warnings, naming what would do: PBF's compression grows about as dt^2 at a fixed count
// of iterations, so dt sqrt(1% / mean) brings it near 1%; WCSPH's density varies as
// (|v| / c0)^2, so c0 = 10 |v|max keeps it near 1%, with dt <= 0.15 h / c0.
std::string pbf_compression_warning(const std::string& fix, double mean, std::int64_t step, double dt, double h,
                                    int iterations);
std::string wcsph_compression_warning(const std::string& fix, double mean, std::int64_t step, double c0, double speed,
                                      double h);

}  // namespace pbf

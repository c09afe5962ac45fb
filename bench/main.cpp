// pbf_bench's main: Google Benchmark's, plus the FMA peak the micro-benchmarks' peak_fraction
// divides by, measured first (about 0.2 s) and shown in the context lines of the output.
// PBF_BENCH_PEAK_GFLOPS=X takes X GFLOP/s (all threads) instead; =0 leaves peak_fraction out.
#include <benchmark/benchmark.h>
#include <omp.h>
#include <spdlog/spdlog.h>

#include <cstdlib>
#include <string>

#include "bench/fma_peak.hpp"
#include "engine/core/real.hpp"
#include "engine/core/threads.hpp"

namespace pbf::bench {
double g_peak_flops = 0;
}

int main(int argc, char** argv) {
  using namespace pbf::bench;
  pbf::restart_with_polite_waiting(argv);  // threads wait as pbfengine's do (engine/core/threads.hpp)
  spdlog::set_level(spdlog::level::warn);  // sim.run() logs a timing table at info level
  register_fma_peak_benchmarks();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;

  constexpr bool is_double = sizeof(pbf::real) == 8;
  const char* precision = is_double ? "double" : "float";
  benchmark::AddCustomContext("pbf_real", precision);
  benchmark::AddCustomContext("omp_threads", std::to_string(omp_get_max_threads()));
  benchmark::AddCustomContext("fma_isa", best_isa());
  if (const char* given = std::getenv("PBF_BENCH_PEAK_GFLOPS")) {
    g_peak_flops = std::atof(given) * 1e9;
    benchmark::AddCustomContext("peak_fraction_of_gflops", std::string(given) + " (PBF_BENCH_PEAK_GFLOPS)");
  } else {
    // peak_fraction divides by one thread's peak times the thread count: FMA units do not
    // share anything between cores, and a measurement on every thread is at the mercy of
    // whatever else runs on the machine (the all-threads figure is shown too).
    const double one = measure_peak_flops(is_double, false, 0.1);
    const double all = measure_peak_flops(is_double, true, 0.1);
    g_peak_flops = one * omp_get_max_threads();
    benchmark::AddCustomContext(std::string("fma_peak_1_thread_gflops_") + precision, std::to_string(one * 1e-9));
    benchmark::AddCustomContext(std::string("fma_peak_all_threads_gflops_") + precision, std::to_string(all * 1e-9));
    benchmark::AddCustomContext("peak_fraction_of_gflops", std::to_string(g_peak_flops * 1e-9) + " (1 thread x " +
                                                               std::to_string(omp_get_max_threads()) + ")");
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

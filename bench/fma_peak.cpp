// fma_peak: the peak floating-point rate of this machine, per core and on every core.
//
// K independent chains acc_k = acc_k * a + b on SIMD vectors (GCC vector extensions), K at
// least latency x throughput of the FMA units (4 cycles x 2 units on Zen 4 and recent Intel
// cores: 8; 12 for AVX2, 24 for AVX-512, 14 for SSE2's multiply and add), so the units
// never wait for a result. a = 0.999 and b = 0.001 keep every chain near its fixed point 1:
// no overflow, no subnormals. a and b come from volatile loads through a call the compiler
// cannot see into, and the chains' sum goes to benchmark::DoNotOptimize, so none of the work
// can be folded or dropped.
//
// Each instruction set is one kernel compiled with a target attribute (this file needs no
// -march) and run only when __builtin_cpu_supports says the CPU has it. bench/CMakeLists.txt
// compiles this file with -ffp-contract=fast, so a * b + c becomes one FMA instruction
// (vfmadd...ps/pd; objdump -d shows the loop); "sse2" has no FMA and runs a multiply and an
// add (2 flops too), what code built without -march and without run-time dispatch can use.
#include "bench/fma_peak.hpp"

#include <benchmark/benchmark.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <string>

namespace pbf::bench {

namespace {

typedef float f32x4 __attribute__((vector_size(16)));
typedef float f32x8 __attribute__((vector_size(32)));
typedef float f32x16 __attribute__((vector_size(64)));
typedef double f64x2 __attribute__((vector_size(16)));
typedef double f64x4 __attribute__((vector_size(32)));
typedef double f64x8 __attribute__((vector_size(64)));

// `rounds` rounds of K chained multiply-adds on vectors V of T; returns the sum of the lanes.
// Inlined into each kernel below, so it compiles for that kernel's instruction set.
template <class V, class T, int K>
[[gnu::always_inline]] inline T chains(long rounds, T a, T b) {
  const V va = V{} + a, vb = V{} + b;
  V acc[K];
#pragma GCC unroll 32
  for (int k = 0; k < K; ++k) acc[k] = V{} + T(1 + 0.01 * k);
  for (long r = 0; r < rounds; ++r) {
#pragma GCC unroll 32
    for (int k = 0; k < K; ++k) acc[k] = acc[k] * va + vb;
  }
  V sum = acc[0];
#pragma GCC unroll 32
  for (int k = 1; k < K; ++k) sum += acc[k];
  T total = 0;
  for (unsigned l = 0; l < sizeof(V) / sizeof(T); ++l) total += sum[l];
  return total;
}

// One kernel per instruction set and type; the K accumulators, a and b stay in registers
// (16 xmm or ymm, 32 zmm). SSE2 is x86-64's baseline: no target attribute.
#define PBF_FMA_KERNEL(NAME, TARGET, V, T, K)                                                    \
  __attribute__((target(TARGET), noinline)) T NAME(long rounds, T a, T b) {                      \
    return chains<V, T, K>(rounds, a, b);                                                        \
  }
__attribute__((noinline)) double sse2_double(long rounds, double a, double b) {
  return chains<f64x2, double, 14>(rounds, a, b);
}
__attribute__((noinline)) float sse2_float(long rounds, float a, float b) {
  return chains<f32x4, float, 14>(rounds, a, b);
}
PBF_FMA_KERNEL(avx2_double, "avx2,fma", f64x4, double, 12)
PBF_FMA_KERNEL(avx2_float, "avx2,fma", f32x8, float, 12)
PBF_FMA_KERNEL(avx512_double, "avx512f,fma", f64x8, double, 24)
PBF_FMA_KERNEL(avx512_float, "avx512f,fma", f32x16, float, 24)
#undef PBF_FMA_KERNEL

struct Isa {
  const char* name;
  bool (*supported)();
  double (*kernel_double)(long, double, double);
  float (*kernel_float)(long, float, float);
  int chains, bytes;  // independent chains, vector width
  // flops of one round: chains x lanes x 2
  double flops_per_round(bool is_double) const { return 2.0 * chains * bytes / (is_double ? 8 : 4); }
};

const Isa kIsas[] = {
    {"avx512", [] { return bool(__builtin_cpu_supports("avx512f")); }, avx512_double, avx512_float, 24, 64},
    {"avx2", [] { return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"); }, avx2_double,
     avx2_float, 12, 32},
    {"sse2", [] { return true; }, sse2_double, sse2_float, 14, 16},
};

constexpr long kRounds = 1 << 16;  // per thread and benchmark iteration: about 0.1-1 ms

// Runs `rounds` rounds on `threads` threads (1: on the calling thread, no parallel region).
template <class T>
T run_kernel(T (*kernel)(long, T, T), long rounds, int threads) {
  static volatile T a_source = T(0.999), b_source = T(0.001);
  const T a = a_source, b = b_source;
  if (threads == 1) return kernel(rounds, a, b);
  T total = 0;
#pragma omp parallel num_threads(threads) reduction(+ : total)
  total += kernel(rounds, a, b);
  return total;
}

template <class T>
void fma_peak(benchmark::State& state, const Isa& isa, bool all_threads) {
  T (*kernel)(long, T, T) = nullptr;
  if constexpr (sizeof(T) == 8) kernel = isa.kernel_double;
  else kernel = isa.kernel_float;
  const int threads = all_threads ? omp_get_max_threads() : 1;
  for (auto _ : state) {
    T r = run_kernel(kernel, kRounds, threads);
    benchmark::DoNotOptimize(r);
  }
  const double flops =
      static_cast<double>(state.iterations()) * kRounds * threads * isa.flops_per_round(sizeof(T) == 8);
  state.counters["flops"] = benchmark::Counter(flops, benchmark::Counter::kIsRate);
  state.counters["flops_per_thread"] = benchmark::Counter(flops / threads, benchmark::Counter::kIsRate);
  state.counters["threads"] = threads;
}

const Isa& best() {
  for (const Isa& isa : kIsas)
    if (isa.supported()) return isa;
  return kIsas[std::size(kIsas) - 1];
}

}  // namespace

void register_fma_peak_benchmarks() {
  __builtin_cpu_init();
  for (const Isa& isa : kIsas) {
    if (!isa.supported()) continue;
    for (bool all : {false, true}) {
      const std::string suffix = std::string("/") + isa.name + (all ? "/all_threads" : "");
      benchmark::RegisterBenchmark(("fma_peak/double" + suffix).c_str(),
                                   [&isa, all](benchmark::State& s) { fma_peak<double>(s, isa, all); })
          ->UseRealTime();
      benchmark::RegisterBenchmark(("fma_peak/float" + suffix).c_str(),
                                   [&isa, all](benchmark::State& s) { fma_peak<float>(s, isa, all); })
          ->UseRealTime();
    }
  }
}

const char* best_isa() {
  __builtin_cpu_init();
  return best().name;
}

double measure_peak_flops(bool double_precision, bool all_threads, double seconds) {
  __builtin_cpu_init();
  const Isa& isa = best();
  const int threads = all_threads ? omp_get_max_threads() : 1;
  using Clock = std::chrono::steady_clock;
  double most = 0;
  for (int attempt = 0; attempt < 3; ++attempt) {
    const auto start = Clock::now();
    long calls = 0;
    double elapsed = 0;
    do {
      if (double_precision) {
        double r = run_kernel(isa.kernel_double, kRounds, threads);
        benchmark::DoNotOptimize(r);
      } else {
        float r = run_kernel(isa.kernel_float, kRounds, threads);
        benchmark::DoNotOptimize(r);
      }
      ++calls;
      elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    } while (elapsed < seconds / 3);
    const double flops = static_cast<double>(calls) * kRounds * threads * isa.flops_per_round(double_precision);
    most = std::max(most, flops / elapsed);
  }
  return most;
}

}  // namespace pbf::bench

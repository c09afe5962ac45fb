#pragma once
// The machine's peak floating-point rate (bench/fma_peak.cpp): independent chains of fused
// multiply-adds on the widest vectors the CPU runs, on one thread or on every OpenMP thread.

namespace pbf::bench {

// Registers the fma_peak benchmarks for each instruction set this CPU supports.
void register_fma_peak_benchmarks();

// The widest instruction set with FMA this CPU runs ("avx512", "avx2", or "sse2" without FMA).
const char* best_isa();

// Peak flop/s (2 per FMA) measured for about `seconds` with the best instruction set, in
// double or single precision, on one thread or on all OpenMP threads (omp_get_max_threads),
// the best of a few tries.
double measure_peak_flops(bool double_precision, bool all_threads, double seconds);

}  // namespace pbf::bench

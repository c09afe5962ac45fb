#pragma once
// The vector instructions the pair loops use (engine/sph/pair_sums.hpp): by default the widest
// this machine has, chosen at run time. A narrower choice gives the same bits (the sums group
// their terms the same way at every width) and lets a test or a user check that it does.
#include <string>
#include <vector>

namespace pbf {

// The choices this machine supports, widest first ("avx512", "avx2", "sse4", "none").
std::vector<std::string> vector_choices();
// Uses vectors no wider than `name` ("auto": the widest). Throws Error for a name that is not
// a choice of this machine.
void limit_vectors(const std::string& name);
// The instruction set in use, as Highway names it (for example "AVX3", "AVX2", "EMU128").
std::string vectors_in_use();

}  // namespace pbf

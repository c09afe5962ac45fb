// Fuzz target: .vtu particle files (engine/io/vtu_read.cpp), through the particle input
// (fuzz_particles.hpp).
#include "fuzz_particles.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const pbf::fuzz::InputFile input("particles.vtu");
  pbf::fuzz::load_particles(input, data, size);
  return 0;
}

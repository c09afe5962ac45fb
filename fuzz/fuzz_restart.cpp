// Fuzz target: restart files (engine/io/restart.cpp), read into a simulation. An input is
// either restored, with a clock a run can continue from, or refused with a pbf::Error
// naming the file and leaving the simulation untouched.
//
// A restart's header holds the CRC-32 and the size of the payload, which random mutations
// would almost never get right: the input's header is patched with the right ones before
// it is written, so the mutations reach the payload reader. (The header checks themselves
// are a few comparisons, covered by tests/test_restart.cpp.)
#include <cmath>
#include <cstring>
#include <vector>
#include <zlib.h>

#include "engine/core/error.hpp"
#include "engine/core/simulation.hpp"
#include "engine/io/restart.hpp"
#include "fuzz_input.hpp"

using namespace pbf;

namespace {

constexpr std::size_t kHeaderBytes = 32, kCrcAt = 20, kSizeAt = 24;  // the layout in restart.hpp

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const fuzz::InputFile input("fuzz.restart");
  std::vector<std::uint8_t> bytes(data, data + size);
  if (size >= kHeaderBytes) {
    const std::uint64_t payload = size - kHeaderBytes;
    const auto crc = static_cast<std::uint32_t>(crc32_z(0, bytes.data() + kHeaderBytes, payload));
    std::memcpy(&bytes[kCrcAt], &crc, sizeof crc);
    std::memcpy(&bytes[kSizeAt], &payload, sizeof payload);
  }
  const std::string& path = input.write(bytes.data(), bytes.size());
  Simulation sim;
  try {
    const RestartSummary summary = read_restart(sim, path);
    fuzz::check(summary.step >= 0 && summary.step == sim.step(), "the step read is negative or not the one set");
    fuzz::check(std::isfinite(sim.time()), "the time read is not finite");
    fuzz::check(summary.particles == sim.particles().size(), "the particle count read is not the one set");
  } catch (const Error& e) {
    fuzz::check_names(e, path);
    fuzz::check(sim.particles().size() == 0 && sim.kernel_radius() == 0 && sim.step() == 0,
                "a refused restart changed the simulation");
  }
  return 0;
}

#pragma once
// Restart files: everything a run needs to continue bit for bit. Binary, in one piece:
//
//   header (32 bytes): magic "\x89PBFRST\n", format version (u32), byte-order mark
//   0x01020304 (u32), size of a real in bytes (u32), CRC-32 of the payload (u32),
//   payload size in bytes (u64)
//   payload: domain lo[3] hi[3], kernel radius, time step, rest density (f64); the clock
//   (step, step_base i64, time_base f64); since version 2, the periodic axes and open faces
//   (u32: bit a for axis a periodic, bit 3 + f for face f open; f = 2 a for the lower face,
//   2 a + 1 for the upper) and the next id to give (i64: ids are never reused, so those saved
//   may have gaps); the particle count N (u64), ids (N i64); the fields (count u32, then name, components u32, N reals per component); the fixes' saved
//   states (count u32, then id, style, size u64, bytes). Strings are u64 length + bytes.
//
// One process saves the particles in memory order, the ranks of a distributed run in id order
// (engine/distributed/restart_write.hpp); neither order changes what a continued run computes,
// as the neighbour lists order particles by cell and id. Any build reads either, on one process
// or on any number of ranks (every rank reads the file; each keeps its part at the next run).
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/core/real.hpp"

namespace pbf {

class Simulation;

// The version written; version 1 (no periodic axes, ids 0..N-1) still reads.
constexpr std::uint32_t kRestartVersion = 2;

struct RestartSummary {
  std::int64_t step = 0;
  double time = 0;
  std::size_t particles = 0;
  std::size_t bytes = 0;  // file size
  double seconds = 0;     // wall time the write or read took
};

// Writes through PATH.tmp, flushed to disk, then an atomic rename: a crash or a full disk
// never leaves a damaged file under PATH. Records PATH as the simulation's last restart.
// The fields are written in this build's precision, or in `real_bytes` (4 or 8) when given.
RestartSummary write_restart(Simulation& sim, const std::string& path, std::uint32_t real_bytes = sizeof(real));

// Restores the domain, kernel radius, time step, rest density, clock, particles and saved
// fields, and keeps the fixes' states for the fixes the script declares next. A damaged,
// truncated or foreign file is an error and leaves `sim` as it was. A file of the other
// precision is converted, with a warning (the continuation is then not bit for bit); a value
// beyond single precision is an error.
RestartSummary read_restart(Simulation& sim, const std::string& path);

// The distributed run's writer (engine/distributed/restart_write.cpp), which write_restart calls.
RestartSummary write_restart_distributed(Simulation& sim, const std::string& path, std::uint32_t real_bytes);

}  // namespace pbf

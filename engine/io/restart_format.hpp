#pragma once
// The pieces of the restart format (engine/io/restart.hpp) that the one-process writer and the
// distributed one (engine/distributed/restart_write.hpp) share: the header, the scene before
// the particles, the list of saved fields, the fixes' states after them, the checksum.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/core/particles.hpp"
#include "engine/io/bytes.hpp"

namespace pbf {

class Simulation;

constexpr std::size_t kHeaderBytes = 32;
inline constexpr unsigned char kMagic[8] = {0x89, 'P', 'B', 'F', 'R', 'S', 'T', '\n'};
inline constexpr std::uint32_t kByteOrderMark = 0x01020304, kSwappedByteOrderMark = 0x04030201;

// The 32-byte header: magic, version, byte-order mark, real size, CRC-32 and size of the payload.
std::vector<unsigned char> restart_header(std::uint32_t real_bytes, std::uint32_t crc, std::uint64_t size);
// The payload's start: domain, kernel radius, time step, rest density, clock.
void put_restart_scene(ByteWriter& w, const Simulation& sim);
// The fields a restart saves, in the order it saves them.
std::vector<FieldId> restart_fields(const Particles& P);
// The payload's end: every fix's saved state.
void put_restart_states(ByteWriter& w, const Simulation& sim);
std::uint32_t restart_checksum(const unsigned char* data, std::size_t size);

}  // namespace pbf

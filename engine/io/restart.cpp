#include "engine/io/restart.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <fmt/format.h>
#include <type_traits>
#include <omp.h>
#include <unistd.h>
#include <zlib.h>

#include "engine/core/error.hpp"
#include "engine/io/bytes.hpp"
#include "engine/io/restart_format.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

std::uint32_t restart_checksum(const unsigned char* data, std::size_t size) {
  return static_cast<std::uint32_t>(crc32_z(crc32_z(0L, Z_NULL, 0), data, size));
}

namespace {

std::uint32_t checksum(const unsigned char* data, std::size_t size) { return restart_checksum(data, size); }

// The particle fields in `real_bytes` per value: this build's precision, or the other one.
template <class Value>
void put_values(ByteWriter& w, const real* values, std::uint64_t n) {
  if constexpr (std::is_same_v<Value, real>) {
    w.put_array(values, n);
  } else {
    for (std::uint64_t i = 0; i < n; ++i) w.put(static_cast<Value>(values[i]));
  }
}

}  // namespace

void put_restart_scene(ByteWriter& w, const Simulation& sim) {
  const Domain& d = sim.domain();
  w.put_array(d.lo, 3);
  w.put_array(d.hi, 3);
  w.put(sim.kernel_radius());
  w.put(sim.timestep());
  w.put(sim.rest_density());
  const Clock clock = sim.clock();
  w.put(clock.step);
  w.put(clock.step_base);
  w.put(clock.time_base);
  std::uint32_t faces = 0;  // bits 0-2: periodic axes; bits 3-8: open faces
  for (int a = 0; a < 3; ++a) faces |= d.periodic[a] ? 1u << a : 0u;
  for (int f = 0; f < 6; ++f) faces |= d.open[f] ? 1u << (3 + f) : 0u;
  w.put(faces);
  w.put(sim.particles().next_id());
}

std::vector<FieldId> restart_fields(const Particles& P) {
  std::vector<FieldId> saved;
  for (FieldId f : P.fields())
    if (P.spec(f).restart) saved.push_back(f);
  return saved;
}

void put_restart_states(ByteWriter& w, const Simulation& sim) {
  const auto& fixes = sim.fixes();
  w.put(static_cast<std::uint32_t>(std::count_if(fixes.begin(), fixes.end(), [](const auto& f) { return f->in_restarts(); })));
  for (const auto& fix : fixes) {
    if (!fix->in_restarts()) continue;
    ByteWriter state;
    fix->save_state(state);
    w.put_string(fix->id());
    w.put_string(fix->style());
    w.put<std::uint64_t>(state.bytes().size());
    w.append(state.bytes().data(), state.bytes().size());
  }
}

std::vector<unsigned char> restart_header(std::uint32_t real_bytes, std::uint32_t crc, std::uint64_t size) {
  ByteWriter header;
  header.put_array(kMagic, 8);
  header.put(kRestartVersion);
  header.put(kByteOrderMark);
  header.put(real_bytes);
  header.put(crc);
  header.put<std::uint64_t>(size);
  return header.bytes();
}

namespace {

std::vector<unsigned char> payload(const Simulation& sim, std::uint32_t real_bytes) {
  ByteWriter w;
  put_restart_scene(w, sim);
  const Particles& P = sim.particles();
  const std::uint64_t n = P.size();
  w.put(n);
  w.put_array(P.ids(), n);
  const std::vector<FieldId> saved = restart_fields(P);
  w.put(static_cast<std::uint32_t>(saved.size()));
  for (FieldId f : saved) {
    w.put_string(P.spec(f).name);
    w.put(static_cast<std::uint32_t>(P.spec(f).components));
    for (int c = 0; c < P.spec(f).components; ++c) {
      if (real_bytes == 4)
        put_values<float>(w, P.data(f, c), n);
      else
        put_values<double>(w, P.data(f, c), n);
    }
  }

  put_restart_states(w, sim);
  return w.bytes();
}

// Writes all of `bytes` to `fd`, retrying short writes.
bool write_all(int fd, const unsigned char* bytes, std::size_t size) {
  while (size > 0) {
    const ssize_t done = ::write(fd, bytes, size);
    if (done < 0 && errno == EINTR) continue;
    if (done <= 0) return false;
    bytes += done;
    size -= static_cast<std::size_t>(done);
  }
  return true;
}

}  // namespace

RestartSummary write_restart(Simulation& sim, const std::string& path, std::uint32_t real_bytes) {
  if (real_bytes != 4 && real_bytes != 8)
    throw Error(fmt::format("write_restart: a real has 4 or 8 bytes, not {}", real_bytes));
  sim.outputs().wrote("restarts", path);
  if (sim.particles().distributed()) return write_restart_distributed(sim, path, real_bytes);
  const double start = omp_get_wtime();
  const std::vector<unsigned char> data = payload(sim, real_bytes);
  const std::vector<unsigned char> header = restart_header(real_bytes, checksum(data.data(), data.size()), data.size());

  const std::string tmp = path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) throw Error(fmt::format("cannot write restart '{}': {}", tmp, std::strerror(errno)));
  bool ok = write_all(fd, header.data(), header.size()) && write_all(fd, data.data(), data.size());
  const int write_errno = errno;
  ok = ::fsync(fd) == 0 && ok;  // on disk before the rename makes it the newest restart
  ok = ::close(fd) == 0 && ok;
  if (!ok) {
    ::unlink(tmp.c_str());
    throw Error(fmt::format("cannot write restart '{}': {} (disk full?)", path, std::strerror(write_errno)));
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int e = errno;
    ::unlink(tmp.c_str());
    throw Error(fmt::format("cannot rename '{}' to '{}': {}", tmp, path, std::strerror(e)));
  }
  sim.set_last_restart({path, sim.step()});
  return {sim.step(), sim.time(), sim.particles().size(), kHeaderBytes + data.size(), omp_get_wtime() - start};
}

}  // namespace pbf

#include "engine/io/restart.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fmt/format.h>
#include <omp.h>
#include <unistd.h>
#include <zlib.h>

#include "engine/core/error.hpp"
#include "engine/io/bytes.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

namespace {

constexpr unsigned char kMagic[8] = {0x89, 'P', 'B', 'F', 'R', 'S', 'T', '\n'};
constexpr std::uint32_t kByteOrderMark = 0x01020304, kSwappedByteOrderMark = 0x04030201;
constexpr std::size_t kHeaderBytes = 32;

std::uint32_t checksum(const unsigned char* data, std::size_t size) {
  return static_cast<std::uint32_t>(crc32_z(crc32_z(0L, Z_NULL, 0), data, size));
}

std::vector<unsigned char> payload(const Simulation& sim) {
  ByteWriter w;
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

  const Particles& P = sim.particles();
  const std::uint64_t n = P.size();
  w.put(n);
  w.put_array(P.ids(), n);
  std::vector<FieldId> saved;
  for (FieldId f : P.fields())
    if (P.spec(f).restart) saved.push_back(f);
  w.put(static_cast<std::uint32_t>(saved.size()));
  for (FieldId f : saved) {
    w.put_string(P.spec(f).name);
    w.put(static_cast<std::uint32_t>(P.spec(f).components));
    for (int c = 0; c < P.spec(f).components; ++c) w.put_array(P.data(f, c), n);
  }

  w.put(static_cast<std::uint32_t>(sim.fixes().size()));
  for (const auto& fix : sim.fixes()) {
    ByteWriter state;
    fix->save_state(state);
    w.put_string(fix->id());
    w.put_string(fix->style());
    w.put<std::uint64_t>(state.bytes().size());
    w.append(state.bytes().data(), state.bytes().size());
  }
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

std::vector<unsigned char> read_file(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw Error(what + (std::filesystem::exists(path, ec) ? ": not a regular file" : ": no such file"));
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw Error(fmt::format("{}: cannot open it ({})", what, std::strerror(errno)));
  std::vector<unsigned char> bytes(std::filesystem::file_size(path, ec));
  const std::size_t got = std::fread(bytes.data(), 1, bytes.size(), f);
  std::fclose(f);
  if (ec || got != bytes.size()) throw Error(what + ": cannot read it");
  return bytes;
}

void check_header(ByteReader& header, std::size_t file_size, const std::string& what, std::uint32_t& crc,
                  std::uint64_t& size) {
  unsigned char magic[8];
  header.get_into(magic, 8);
  if (std::memcmp(magic, kMagic, 8) != 0) throw Error(what + ": not a pbfengine restart file");
  const auto version = header.get<std::uint32_t>(), order = header.get<std::uint32_t>(),
             real_bytes = header.get<std::uint32_t>();
  crc = header.get<std::uint32_t>();
  size = header.get<std::uint64_t>();
  if (order == kSwappedByteOrderMark)
    throw Error(what + ": written on a machine of the other byte order; restarts are not portable across it");
  if (order != kByteOrderMark) throw Error(what + ": the header is damaged (bad byte-order mark)");
  if (version != kRestartVersion)
    throw Error(fmt::format("{}: restart format version {}; this pbfengine reads version {}", what, version,
                            kRestartVersion));
  if (real_bytes != sizeof(real)) {
    auto name = [](std::uint32_t bytes) { return bytes == 4 ? "single (float)" : bytes == 8 ? "double" : "unknown"; };
    throw Error(fmt::format("{}: written by a {}-precision build, this build is {} precision "
                            "(configure with -DPBF_REAL={} to read it)",
                            what, name(real_bytes), name(sizeof(real)), real_bytes == 4 ? "float" : "double"));
  }
  if (size != file_size - kHeaderBytes)
    throw Error(fmt::format("{}: the header announces {} bytes of data but the file holds {} (truncated or damaged)",
                            what, size, file_size - kHeaderBytes));
}

}  // namespace

RestartSummary write_restart(Simulation& sim, const std::string& path) {
  const double start = omp_get_wtime();
  const std::vector<unsigned char> data = payload(sim);
  ByteWriter header;
  header.put_array(kMagic, 8);
  header.put(kRestartVersion);
  header.put(kByteOrderMark);
  header.put(static_cast<std::uint32_t>(sizeof(real)));
  header.put(checksum(data.data(), data.size()));
  header.put<std::uint64_t>(data.size());

  const std::string tmp = path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) throw Error(fmt::format("cannot write restart '{}': {}", tmp, std::strerror(errno)));
  bool ok = write_all(fd, header.bytes().data(), header.bytes().size()) && write_all(fd, data.data(), data.size());
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

RestartSummary read_restart(Simulation& sim, const std::string& path) {
  const double start = omp_get_wtime();
  const std::string what = fmt::format("restart file '{}'", path);
  const std::vector<unsigned char> bytes = read_file(path, what);
  if (bytes.size() < kHeaderBytes)
    throw Error(fmt::format("{}: {} bytes, too short to be a restart file", what, bytes.size()));
  ByteReader header(bytes.data(), kHeaderBytes, what);
  std::uint32_t crc = 0;
  std::uint64_t size = 0;
  check_header(header, bytes.size(), what, crc, size);
  const unsigned char* data = bytes.data() + kHeaderBytes;
  if (checksum(data, size) != crc) throw Error(what + ": the data are corrupted (checksum mismatch)");

  // Everything is read into locals first: a file that fails half way changes nothing.
  ByteReader r(data, size, what);
  Domain domain;
  r.get_into(domain.lo, 3);
  r.get_into(domain.hi, 3);
  const auto h = r.get<double>(), dt = r.get<double>(), rho0 = r.get<double>();
  Clock clock;
  clock.step = r.get<std::int64_t>();
  clock.step_base = r.get<std::int64_t>();
  clock.time_base = r.get<double>();

  const auto n = r.get<std::uint64_t>();
  std::vector<std::int64_t> ids;
  r.get_array(ids, n);
  Particles particles;
  try {
    particles.reset(std::move(ids));
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", what, e.what()));
  }
  const auto field_count = r.get<std::uint32_t>();
  std::vector<std::string> names;
  for (std::uint32_t k = 0; k < field_count; ++k) {
    FieldSpec spec;
    spec.name = r.get_string();
    const auto components = r.get<std::uint32_t>();
    if (spec.name.empty() || components < 1 || components > 64)
      throw Error(fmt::format("{}: field {} is damaged (name '{}', {} components)", what, k, spec.name, components));
    spec.components = static_cast<int>(components);
    r.require(n * components, sizeof(real));
    FieldId f;
    try {
      f = particles.declare(spec);
    } catch (const Error& e) {
      throw Error(fmt::format("{}: {}", what, e.what()));
    }
    for (int c = 0; c < spec.components; ++c) r.get_into(particles.data(f, c), n);
    names.push_back(spec.name);
  }
  for (const char* core : {"position", "velocity", "mass"})
    if (std::find(names.begin(), names.end(), core) == names.end())
      throw Error(fmt::format("{}: the particles' {} is missing", what, core));
  for (std::size_t i = 0; i < n; ++i) {
    const real m = particles.mass()[i];
    if (!(m > 0) || !std::isfinite(m))
      throw Error(fmt::format("{}: particle {} has mass {}", what, particles.ids()[i], m));
    if (!domain.contains(particles.x()[i], particles.y()[i], particles.z()[i]))
      throw Error(fmt::format("{}: particle {} at ({}, {}, {}) is outside the saved domain", what,
                              particles.ids()[i], particles.x()[i], particles.y()[i], particles.z()[i]));
  }

  const auto state_count = r.get<std::uint32_t>();
  r.require(state_count, 3 * sizeof(std::uint64_t));  // each state has at least its three sizes
  std::vector<SavedFixState> states(state_count);
  for (auto& s : states) {
    s.id = r.get_string();
    s.style = r.get_string();
    r.get_array(s.bytes, r.get<std::uint64_t>());
  }
  if (r.left() != 0) throw Error(fmt::format("{}: {} bytes of unexpected data at the end", what, r.left()));

  Simulation probe;  // the setters' checks, without touching `sim` yet
  try {
    probe.set_domain(domain);
    probe.set_kernel_radius(h);
    probe.set_timestep(dt);
    probe.set_rest_density(rho0);
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", what, e.what()));
  }
  sim.set_domain(domain);
  sim.set_kernel_radius(h);
  sim.set_timestep(dt);
  sim.set_rest_density(rho0);
  sim.set_clock(clock);
  sim.particles() = std::move(particles);
  sim.positions_changed();
  sim.set_saved_states(std::move(states), path);
  sim.set_last_restart({path, clock.step});
  return {clock.step, sim.time(), sim.particles().size(), bytes.size(), omp_get_wtime() - start};
}

}  // namespace pbf

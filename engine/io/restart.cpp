#include "engine/io/restart.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <type_traits>
#include <omp.h>
#include <set>
#include <unistd.h>
#include <zlib.h>

#include "engine/core/error.hpp"
#include "engine/io/bytes.hpp"
#include "engine/io/restart_format.hpp"
#include "engine/core/simulation.hpp"
#include "engine/sph/resolution.hpp"

namespace pbf {

namespace {

constexpr unsigned char kMagic[8] = {0x89, 'P', 'B', 'F', 'R', 'S', 'T', '\n'};
constexpr std::uint32_t kByteOrderMark = 0x01020304, kSwappedByteOrderMark = 0x04030201;

}  // namespace

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
}

std::vector<FieldId> restart_fields(const Particles& P) {
  std::vector<FieldId> saved;
  for (FieldId f : P.fields())
    if (P.spec(f).restart) saved.push_back(f);
  return saved;
}

void put_restart_states(ByteWriter& w, const Simulation& sim) {
  w.put(static_cast<std::uint32_t>(sim.fixes().size()));
  for (const auto& fix : sim.fixes()) {
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

std::vector<unsigned char> read_file(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw Error(what + ": is a directory, not a file");
  if (!std::filesystem::is_regular_file(path, ec))
    throw Error(what + (std::filesystem::exists(path, ec) ? ": not a regular file" : ": no such file"));
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw Error(fmt::format("{}: cannot open it ({})", what, std::strerror(errno)));
  // On failure file_size returns -1: check before sizing a vector with it.
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) {
    std::fclose(f);
    throw Error(fmt::format("{}: cannot read it ({})", what, ec.message()));
  }
  std::vector<unsigned char> bytes(size);
  const std::size_t got = size > 0 ? std::fread(bytes.data(), 1, bytes.size(), f) : 0;
  std::fclose(f);
  if (got != bytes.size()) throw Error(what + ": cannot read it (it changed while being read?)");
  return bytes;
}

// The most particle fields a restart may hold (the engine declares about ten).
constexpr std::uint32_t kMaxFields = 1000;

// The largest step a restart may hold. No run comes near it (2^53 steps), a step count
// up to it converts to the double of time() exactly, and a run of any int64 length added
// to it stays far from signed overflow.
constexpr std::int64_t kMaxStep = std::int64_t{1} << 53;

// The clock as a run leaves it: 0 <= step_base <= step <= kMaxStep, time_base finite, and
// so a finite time. A NaN time or a step near the int64 limit (undefined behaviour once
// the run loop counts on) is a damaged file.
void check_clock(const Clock& clock, double dt, const std::string& what) {
  auto damaged = [&](const std::string& why) {
    throw Error(fmt::format("{}: the clock is damaged ({}; step {}, step_base {}, time_base {})", what, why,
                            clock.step, clock.step_base, clock.time_base));
  };
  if (clock.step < 0 || clock.step > kMaxStep) damaged("the step must lie in 0..2^53");
  if (clock.step_base < 0 || clock.step_base > clock.step) damaged("step_base must lie in 0..step");
  if (!std::isfinite(clock.time_base)) damaged("time_base is not finite");
  const double time = clock.time_base + static_cast<double>(clock.step - clock.step_base) * dt;
  if (!std::isfinite(time)) damaged(fmt::format("the time, {}, is not finite", time));
}

// Reads n values stored with `Stored` precision into this build's reals. From double into
// float a finite value beyond float's range is refused, naming the field and the particle.
template <class Stored>
void get_values(ByteReader& r, real* out, std::uint64_t n, const std::string& field, const std::int64_t* ids) {
  if constexpr (std::is_same_v<Stored, real>) {
    r.get_into(out, n);
  } else {
    std::vector<Stored> stored;
    r.get_array(stored, n);
    for (std::uint64_t i = 0; i < n; ++i) {
      out[i] = static_cast<real>(stored[i]);
      if (std::isfinite(stored[i]) && !std::isfinite(out[i]))
        throw Error(fmt::format("{}: field '{}' of particle {} is {}, beyond this build's single precision",
                                r.what(), field, ids[i], stored[i]));
    }
  }
}

void check_header(ByteReader& header, std::size_t file_size, const std::string& what, std::uint32_t& crc,
                  std::uint64_t& size, std::uint32_t& real_bytes) {
  unsigned char magic[8];
  header.get_into(magic, 8);
  if (std::memcmp(magic, kMagic, 8) != 0) throw Error(what + ": not a pbfengine restart file");
  const auto version = header.get<std::uint32_t>(), order = header.get<std::uint32_t>();
  real_bytes = header.get<std::uint32_t>();
  crc = header.get<std::uint32_t>();
  size = header.get<std::uint64_t>();
  if (order == kSwappedByteOrderMark)
    throw Error(what + ": written on a machine of the other byte order; restarts are not portable across it");
  if (order != kByteOrderMark) throw Error(what + ": the header is damaged (bad byte-order mark)");
  if (version != kRestartVersion)
    throw Error(fmt::format("{}: restart format version {}; this pbfengine reads version {}", what, version,
                            kRestartVersion));
  if (real_bytes != 4 && real_bytes != 8)
    throw Error(fmt::format("{}: the header is damaged (a real of {} bytes is no precision pbfengine writes: 4 or 8 "
                            "expected)",
                            what, real_bytes));
  if (size != file_size - kHeaderBytes)
    throw Error(fmt::format("{}: the header announces {} bytes of data but the file holds {} (truncated or damaged)",
                            what, size, file_size - kHeaderBytes));
}

}  // namespace

RestartSummary write_restart(Simulation& sim, const std::string& path, std::uint32_t real_bytes) {
  if (real_bytes != 4 && real_bytes != 8)
    throw Error(fmt::format("write_restart: a real has 4 or 8 bytes, not {}", real_bytes));
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

RestartSummary read_restart(Simulation& sim, const std::string& path) {
  const double start = omp_get_wtime();
  const std::string what = fmt::format("restart file '{}'", path);
  const std::vector<unsigned char> bytes = read_file(path, what);
  if (bytes.size() < kHeaderBytes)
    throw Error(fmt::format("{}: {} bytes, too short to be a restart file", what, bytes.size()));
  ByteReader header(bytes.data(), kHeaderBytes, what);
  std::uint32_t crc = 0;
  std::uint64_t size = 0;
  std::uint32_t real_bytes = 0;
  check_header(header, bytes.size(), what, crc, size, real_bytes);
  const unsigned char* data = bytes.data() + kHeaderBytes;
  if (checksum(data, size) != crc) throw Error(what + ": the data are corrupted (checksum mismatch)");

  // Everything is read into locals first: a file that fails half way changes nothing.
  ByteReader r(data, size, what);
  Domain domain;
  r.get_into(domain.lo, 3);
  r.get_into(domain.hi, 3);
  const auto h = r.get<double>(), dt = r.get<double>(), rho0 = r.get<double>();
  Simulation probe;  // the setters' checks, without touching `sim` yet
  try {
    probe.set_domain(domain);
    probe.set_kernel_radius(h);
    probe.set_timestep(dt);
    probe.set_rest_density(rho0);
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", what, e.what()));
  }
  Clock clock;
  clock.step = r.get<std::int64_t>();
  clock.step_base = r.get<std::int64_t>();
  clock.time_base = r.get<double>();
  check_clock(clock, dt, what);

  const auto n = r.get<std::uint64_t>();
  if (n == 0) throw Error(what + ": it holds no particles (the engine never writes such a file)");
  std::vector<std::int64_t> ids;
  r.get_array(ids, n);
  Particles particles;
  try {
    particles.reset(std::move(ids));
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", what, e.what()));
  }
  const auto field_count = r.get<std::uint32_t>();
  // Each field is one a fix declared: a pipeline has a handful. The bound keeps a damaged
  // count from costing a quadratic search of the declared names.
  if (field_count > kMaxFields)
    throw Error(fmt::format("{}: the field count, {}, is damaged (at most {})", what, field_count, kMaxFields));
  std::vector<std::string> names;
  for (std::uint32_t k = 0; k < field_count; ++k) {
    FieldSpec spec;
    spec.name = r.get_string();
    const auto components = r.get<std::uint32_t>();
    if (spec.name.empty() || components < 1 || components > 64)
      throw Error(fmt::format("{}: field {} is damaged (name '{}', {} components)", what, k, spec.name, components));
    // Declaring a name twice would give the same array, read twice: one of the two is lost.
    if (std::find(names.begin(), names.end(), spec.name) != names.end())
      throw Error(fmt::format("{}: field '{}' is saved twice", what, spec.name));
    spec.components = static_cast<int>(components);
    r.require(n * components, real_bytes);
    FieldId f;
    try {
      f = particles.declare(spec);
    } catch (const Error& e) {
      throw Error(fmt::format("{}: {}", what, e.what()));
    }
    for (int c = 0; c < spec.components; ++c) {
      if (real_bytes == 4)
        get_values<float>(r, particles.data(f, c), n, spec.name, particles.ids());
      else
        get_values<double>(r, particles.data(f, c), n, spec.name, particles.ids());
    }
    names.push_back(spec.name);
  }
  for (const char* core : {"position", "velocity", "mass"})
    if (std::find(names.begin(), names.end(), core) == names.end())
      throw Error(fmt::format("{}: the particles' {} is missing", what, core));
  // What the run loop guarantees of every step it finishes (it stops at a blow-up), so of
  // every restart it writes.
  for (std::size_t i = 0; i < n; ++i) {
    const real m = particles.mass()[i];
    if (!(m > 0) || !std::isfinite(m))
      throw Error(fmt::format("{}: particle {} has mass {}", what, particles.ids()[i], m));
    if (!domain.contains(particles.x()[i], particles.y()[i], particles.z()[i]))
      throw Error(fmt::format("{}: particle {} at ({}, {}, {}) is outside the saved domain", what,
                              particles.ids()[i], particles.x()[i], particles.y()[i], particles.z()[i]));
    if (!std::isfinite(particles.vx()[i]) || !std::isfinite(particles.vy()[i]) || !std::isfinite(particles.vz()[i]))
      throw Error(fmt::format("{}: particle {} has velocity ({}, {}, {}), not finite", what, particles.ids()[i],
                              particles.vx()[i], particles.vy()[i], particles.vz()[i]));
  }

  const auto state_count = r.get<std::uint32_t>();
  r.require(state_count, 3 * sizeof(std::uint64_t));  // each state has at least its three sizes
  std::vector<SavedFixState> states(state_count);
  std::set<std::string> ids_seen;
  for (std::size_t k = 0; k < states.size(); ++k) {
    SavedFixState& s = states[k];
    s.id = r.get_string();
    s.style = r.get_string();
    // A state goes to the fix of its id: an empty or repeated id could never be matched.
    if (s.id.empty() || s.style.empty())
      throw Error(fmt::format("{}: saved fix state {} is damaged (id '{}', style '{}')", what, k, s.id, s.style));
    if (!ids_seen.insert(s.id).second) throw Error(fmt::format("{}: fix '{}' has two saved states", what, s.id));
    r.get_array(s.bytes, r.get<std::uint64_t>());
  }
  if (r.left() != 0) throw Error(fmt::format("{}: {} bytes of unexpected data at the end", what, r.left()));
  // What a lattice or a particle file would have been refused for (a file made by hand).
  try {
    probe.check_scale();
    check_kernel_radius(h, sampled_spacing(particles.x(), particles.y(), particles.z(), n), "the saved particles");
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", what, e.what()));
  }

  // The states first: a fix declared before the read that refuses its state (written by
  // another version of its style) leaves the scene as it was.
  sim.set_saved_states(std::move(states), path);
  sim.set_domain(domain);
  sim.set_kernel_radius(h);
  sim.set_timestep(dt);
  sim.set_rest_density(rho0);
  sim.set_clock(clock);
  sim.particles() = std::move(particles);
  sim.positions_changed();
  sim.set_last_restart({path, clock.step});
  if (real_bytes != sizeof(real))
    spdlog::warn("{}: written in {} precision, read into this {}-precision build: the values are converted, and the "
                 "run continues close to, not bit for bit like, the saved run",
                 what, real_bytes == 4 ? "single" : "double", sizeof(real) == 4 ? "single" : "double");
  return {clock.step, sim.time(), sim.particles().size(), bytes.size(), omp_get_wtime() - start};
}

}  // namespace pbf

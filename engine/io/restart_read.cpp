// Reading a restart (engine/io/restart.hpp for the format). The file is read where it lies, not
// whole into memory: every process reads the header, the scene, the list of fields and the
// fixes' states (small), and of the particle arrays only its share of the records. In one
// process that share is every record; in a distributed run it is a block of about 1/ranks of
// them (Particles::share), which the run's start places on the ranks that own their cells.
// The checksum likewise: each rank computes the CRC-32 of a block of the payload, and the
// blocks' CRCs are combined in file order (zlib's crc32_combine), so that every byte is
// checked once, by one rank.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fmt/format.h>
#include <omp.h>
#include <set>
#include <spdlog/spdlog.h>
#include <sys/stat.h>
#include <type_traits>
#include <unistd.h>
#include <zlib.h>

#include "engine/core/error.hpp"
#include "engine/core/simulation.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/io/restart.hpp"
#include "engine/io/restart_format.hpp"
#include "engine/sph/resolution.hpp"

namespace pbf {

namespace {

// The most particle fields a restart may hold (the engine declares about ten).
constexpr std::uint32_t kMaxFields = 1000;

// The largest step a restart may hold. No run comes near it (2^53 steps), a step count
// up to it converts to the double of time() exactly, and a run of any int64 length added
// to it stays far from signed overflow.
constexpr std::int64_t kMaxStep = std::int64_t{1} << 53;

// A file read item by item at a position that moves on, as ByteReader reads bytes in memory,
// with the same check before every read: nothing past the end (a truncated file is an error
// naming it, never a short read).
class FileReader {
 public:
  FileReader(const std::string& path, std::string what) : what_(std::move(what)) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw Error(what_ + ": is a directory, not a file");
    if (!std::filesystem::is_regular_file(path, ec))
      throw Error(what_ + (std::filesystem::exists(path, ec) ? ": not a regular file" : ": no such file"));
    fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd_ < 0) throw Error(fmt::format("{}: cannot open it ({})", what_, std::strerror(errno)));
    struct stat st {};
    if (::fstat(fd_, &st) != 0) {
      const int e = errno;
      ::close(fd_);
      throw Error(fmt::format("{}: cannot read it ({})", what_, std::strerror(e)));
    }
    size_ = static_cast<std::uint64_t>(st.st_size);
  }
  ~FileReader() { ::close(fd_); }
  FileReader(const FileReader&) = delete;
  FileReader& operator=(const FileReader&) = delete;

  std::uint64_t size() const { return size_; }
  std::uint64_t left() const { return size_ - pos_; }
  const std::string& what() const { return what_; }
  // Throws unless `count` items of `item_size` bytes fit in what is left.
  void require(std::uint64_t count, std::size_t item_size) const {
    if (count > left() / item_size) throw Error(what_ + ": the data end early (the file is truncated or corrupted)");
  }
  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T value;
    get_into(&value, 1);
    return value;
  }
  template <class T>
  void get_into(T* out, std::uint64_t count) {
    require(count, sizeof(T));
    read_at(pos_, out, count * sizeof(T));
    pos_ += count * sizeof(T);
  }
  template <class T>
  void get_array(std::vector<T>& out, std::uint64_t count) {
    require(count, sizeof(T));
    out.resize(count);
    get_into(out.data(), count);
  }
  std::string get_string() {
    const auto n = get<std::uint64_t>();
    require(n, 1);  // before the string allocates n bytes
    std::string s(n, '\0');
    get_into(s.data(), n);
    return s;
  }
  // Items [share.first, share.end) of an array of `count`, then on past the whole array.
  template <class T>
  void get_share(std::vector<T>& out, std::uint64_t count, Particles::Share share) {
    require(count, sizeof(T));
    out.resize(share.end - share.first);
    read_at(pos_ + share.first * sizeof(T), out.data(), out.size() * sizeof(T));
    pos_ += count * sizeof(T);
  }
  // The CRC-32 of `length` bytes from `offset`, read in pieces.
  std::uint32_t crc(std::uint64_t offset, std::uint64_t length) const {
    std::vector<unsigned char> piece(std::min<std::uint64_t>(length, 1 << 22));
    uLong crc = crc32_z(0L, Z_NULL, 0);
    while (length > 0) {
      const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(length, piece.size()));
      read_at(offset, piece.data(), n);
      crc = crc32_z(crc, piece.data(), n);
      offset += n;
      length -= n;
    }
    return static_cast<std::uint32_t>(crc);
  }

 private:
  void read_at(std::uint64_t offset, void* out, std::size_t n) const {
    auto* p = static_cast<char*>(out);
    while (n > 0) {
      const ssize_t got = ::pread(fd_, p, n, static_cast<off_t>(offset));
      if (got < 0 && errno == EINTR) continue;
      if (got < 0) throw Error(fmt::format("{}: cannot read it ({})", what_, std::strerror(errno)));
      if (got == 0) throw Error(what_ + ": cannot read it (it changed while being read?)");
      p += got;
      offset += static_cast<std::uint64_t>(got);
      n -= static_cast<std::size_t>(got);
    }
  }
  int fd_ = -1;
  std::uint64_t size_ = 0, pos_ = 0;
  std::string what_;
};

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

// The 32-byte header; returns the payload's CRC and size, the bytes of a real and the version.
void check_header(FileReader& r, std::uint32_t& crc, std::uint64_t& size, std::uint32_t& real_bytes,
                  std::uint32_t& version) {
  const std::string& what = r.what();
  if (r.size() < kHeaderBytes) throw Error(fmt::format("{}: {} bytes, too short to be a restart file", what, r.size()));
  unsigned char magic[8];
  r.get_into(magic, 8);
  if (std::memcmp(magic, kMagic, 8) != 0) throw Error(what + ": not a pbfengine restart file");
  version = r.get<std::uint32_t>();
  const auto order = r.get<std::uint32_t>();
  real_bytes = r.get<std::uint32_t>();
  crc = r.get<std::uint32_t>();
  size = r.get<std::uint64_t>();
  if (order == kSwappedByteOrderMark)
    throw Error(what + ": written on a machine of the other byte order; restarts are not portable across it");
  if (order != kByteOrderMark) throw Error(what + ": the header is damaged (bad byte-order mark)");
  if (version < 1 || version > kRestartVersion)
    throw Error(fmt::format("{}: restart format version {}; this pbfengine reads versions 1 to {}", what, version,
                            kRestartVersion));
  if (real_bytes != 4 && real_bytes != 8)
    throw Error(fmt::format("{}: the header is damaged (a real of {} bytes is no precision pbfengine writes: 4 or 8 "
                            "expected)",
                            what, real_bytes));
  if (size != r.size() - kHeaderBytes)
    throw Error(fmt::format("{}: the header announces {} bytes of data but the file holds {} (truncated or damaged)",
                            what, size, r.size() - kHeaderBytes));
}

// The payload's CRC-32: each rank's block of it, combined in file order.
std::uint32_t payload_crc(const FileReader& r, std::uint64_t size) {
  const std::uint64_t ranks = static_cast<std::uint64_t>(comm::ranks()), rank = static_cast<std::uint64_t>(comm::rank());
  const std::uint64_t first = size / ranks * rank + std::min(rank, size % ranks);
  const std::uint64_t length = size / ranks + (rank < size % ranks ? 1 : 0);
  const std::int64_t mine[2] = {static_cast<std::int64_t>(r.crc(kHeaderBytes + first, length)),
                                static_cast<std::int64_t>(length)};
  const std::vector<std::int64_t> all = comm::gather_all(mine);
  uLong crc = static_cast<uLong>(all[0]);
  for (std::size_t k = 2; k < all.size(); k += 2)
    crc = crc32_combine64(crc, static_cast<uLong>(all[k]), static_cast<z_off64_t>(all[k + 1]));
  return static_cast<std::uint32_t>(crc);
}

// This process's share of one component of a field stored with `Stored` precision, into this
// build's reals. From double into float a finite value beyond float's range is refused, naming
// the field and the particle.
template <class Stored>
void get_values(FileReader& r, real* out, std::uint64_t n, Particles::Share share, const std::string& field,
                const std::int64_t* ids) {
  std::vector<Stored> stored;
  r.get_share(stored, n, share);
  for (std::size_t i = 0; i < stored.size(); ++i) {
    out[i] = static_cast<real>(stored[i]);
    if (std::isfinite(stored[i]) && !std::isfinite(out[i]))
      throw Error(fmt::format("{}: field '{}' of particle {} is {}, beyond this build's single precision", r.what(),
                              field, ids[i], stored[i]));
  }
}

// The ids of all ranks' shares together must be distinct and in 0..next_id-1 (ids of removed
// particles are gaps). Each rank checks its share, then sends each id to the rank of its block
// of 0..next_id-1, which checks that no two ranks sent the same one.
void check_shared_ids(const std::vector<std::int64_t>& ids, std::int64_t next_id, const std::string& what) {
  try {
    check_ids(ids, next_id);
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", what, e.what()));
  }
  const int R = comm::ranks();
  const auto block = [&](std::int64_t id) {
    return static_cast<std::size_t>(static_cast<unsigned __int128>(id) * static_cast<unsigned>(R) /
                                    static_cast<unsigned __int128>(next_id));
  };
  std::vector<std::vector<char>> send(static_cast<std::size_t>(R)), received;
  for (std::int64_t id : ids) {
    const char* bytes = reinterpret_cast<const char*>(&id);
    send[block(id)].insert(send[block(id)].end(), bytes, bytes + sizeof id);
  }
  comm::all_to_all_bytes(send, received);
  std::vector<std::int64_t> mine;
  for (const auto& from : received)
    for (std::size_t at = 0; at + sizeof(std::int64_t) <= from.size(); at += sizeof(std::int64_t)) {
      std::int64_t id = 0;
      std::memcpy(&id, from.data() + at, sizeof id);
      mine.push_back(id);
    }
  std::sort(mine.begin(), mine.end());
  const auto twice = std::adjacent_find(mine.begin(), mine.end());
  const std::int64_t repeated = twice == mine.end() ? -1 : *twice;
  const auto first = static_cast<std::int64_t>(comm::max(static_cast<double>(repeated)));
  if (first >= 0) throw Error(fmt::format("{}: particle id {} is held twice", what, first));
}

}  // namespace

RestartSummary read_restart(Simulation& sim, const std::string& path) {
  const double start = omp_get_wtime();
  const std::string what = fmt::format("restart file '{}'", path);
  FileReader r(path, what);
  std::uint32_t crc = 0;
  std::uint64_t size = 0;
  std::uint32_t real_bytes = 0, version = 0;
  check_header(r, crc, size, real_bytes, version);
  if (payload_crc(r, size) != crc) throw Error(what + ": the data are corrupted (checksum mismatch)");

  // Everything is read into locals first: a file that fails half way changes nothing.
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
  std::int64_t next_id = -1;  // (version 1: the ids were 0..n-1)
  if (version >= 2) {
    const auto faces = r.get<std::uint32_t>();  // bits 0-2: periodic axes; bits 3-8: open faces
    bool damaged = faces >= 1u << 9;
    for (int a = 0; a < 3; ++a) {
      domain.periodic[a] = (faces >> a) & 1u;
      domain.open[2 * a] = (faces >> (3 + 2 * a)) & 1u;
      domain.open[2 * a + 1] = (faces >> (4 + 2 * a)) & 1u;
      damaged = damaged || (domain.periodic[a] && (domain.open[2 * a] || domain.open[2 * a + 1]));
    }
    if (damaged) throw Error(fmt::format("{}: the periodic axes and open faces ({:#x}) are damaged", what, faces));
    next_id = r.get<std::int64_t>();
  }

  const auto n = r.get<std::uint64_t>();
  if (n == 0 && version < 2) throw Error(what + ": it holds no particles (version 1 never held none)");
  if (version < 2) next_id = static_cast<std::int64_t>(n);
  if (next_id < 0 || static_cast<std::uint64_t>(next_id) < n)
    throw Error(fmt::format("{}: the next id, {}, is damaged (the file holds {} particles)", what, next_id, n));
  Particles particles;
  const Particles::Share share = particles.share(n);
  std::vector<std::int64_t> ids;
  r.get_share(ids, n, share);
  if (particles.distributed()) {
    check_shared_ids(ids, next_id, what);
    particles.reset_share(std::move(ids), n, next_id);
  } else {
    try {
      particles.reset(std::move(ids), next_id);
    } catch (const Error& e) {
      throw Error(fmt::format("{}: {}", what, e.what()));
    }
  }
  const std::size_t mine = particles.size();
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
        get_values<float>(r, particles.data(f, c), n, share, spec.name, particles.ids());
      else
        get_values<double>(r, particles.data(f, c), n, share, spec.name, particles.ids());
    }
    names.push_back(spec.name);
  }
  for (const char* core : {"position", "velocity", "mass"})
    if (std::find(names.begin(), names.end(), core) == names.end())
      throw Error(fmt::format("{}: the particles' {} is missing", what, core));
  // What the run loop guarantees of every step it finishes (it stops at a blow-up), so of
  // every restart it writes.
  for (std::size_t i = 0; i < mine; ++i) {
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
    if (n > 0)
      check_kernel_radius(h, sampled_spacing_of_shares(particles.x(), particles.y(), particles.z(), mine,
                                                     particles.distributed()),
                        "the saved particles");
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
  sim.set_last_restart({path, clock.step, true});
  if (real_bytes != sizeof(real))
    spdlog::warn("{}: written in {} precision, read into this {}-precision build: the values are converted, and the "
                 "run continues close to, not bit for bit like, the saved run",
                 what, real_bytes == 4 ? "single" : "double", sizeof(real) == 4 ? "single" : "double");
  return {clock.step, sim.time(), sim.global_count(), r.size(), omp_get_wtime() - start};
}

}  // namespace pbf

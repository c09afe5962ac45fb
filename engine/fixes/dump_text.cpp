// dump/text: the original study's frames, frame_00000.txt, frame_00001.txt, ...: line 1 the
// particle count N, then N lines "x y z vx vy vz" in input (id) order, each number in the
// shortest form that reads back to the same value. With other fields, each line holds
// their components in the order given, after a "# names" comment line.
#include <algorithm>

#include <fmt/format.h>
#include <omp.h>

#include "engine/distributed/lines_by_id.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/output/dump.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

namespace {

const Names kOriginalFields = {"position", "velocity"};
constexpr std::size_t kBlockLines = 16384;

class DumpText : public Dump {
 public:
  DumpText(const std::string& id, const Params& p) : Dump(id, "dump/text", p) {}
  bool runs_distributed() const override { return true; }  // one file, written by every rank

 private:
  void write_frame(Simulation& sim, const std::string& path, std::int64_t) override {
    const std::size_t n = sim.particles().size();
    std::vector<std::vector<real>> values(fields().size());
    fmt::memory_buffer buf;
    if (fields().names() != kOriginalFields) {
      fmt::format_to(std::back_inserter(buf), "#");
      for (std::size_t k = 0; k < fields().size(); ++k) {
        const int nc = fields().components(k);
        for (int c = 0; c < nc; ++c) {
          if (nc == 1) fmt::format_to(std::back_inserter(buf), " {}", fields().names()[k]);
          else fmt::format_to(std::back_inserter(buf), " {}.{}", fields().names()[k], c);
        }
      }
      fmt::format_to(std::back_inserter(buf), "\n");
    }
    if (sim.particles().distributed()) return write_distributed(sim, path, buf);
    // Lines in id order. A particle field is read where it lies, through the memory index of
    // each line's particle; only derived quantities (speed, density, ...) are gathered, so that
    // a frame of position and velocity costs no copy of the particles (memory is the limit at
    // a million of them).
    const auto& P = sim.particles();
    const std::vector<std::uint32_t> index = P.order_by_id();
    std::vector<std::vector<const real*>> columns(fields().size());
    for (std::size_t k = 0; k < fields().size(); ++k) {
      if (fields().is_id(k)) continue;
      if (const auto f = P.find(fields().names()[k])) {
        for (int c = 0; c < fields().components(k); ++c) columns[k].push_back(P.data(*f, c));
      } else {
        fields().gather(sim, k, values[k]);
      }
    }
    fmt::format_to(std::back_inserter(buf), "{}\n", n);
    AtomicFile file(path);  // a full disk leaves no cut-off frame behind
    file.write(buf.data(), buf.size());
    // Formatting numbers is the cost: each thread formats one contiguous range of lines into
    // its own buffer, and the buffers are written in order, so the file is the same bytes.
    // A block of lines at a time, so that the text never takes more memory than one block's.
    const int chunks = omp_get_max_threads();
    std::vector<fmt::memory_buffer> lines(static_cast<std::size_t>(chunks));
    for (std::size_t first = 0; first < n; first += kBlockLines) {
      const std::size_t count = std::min(kBlockLines, n - first);
#pragma omp parallel for schedule(static, 1)
      for (int chunk = 0; chunk < chunks; ++chunk) {
        auto& text = lines[static_cast<std::size_t>(chunk)];
        text.clear();
        auto out = std::back_inserter(text);
        for (std::size_t i = first + count * chunk / chunks; i < first + count * (chunk + 1) / chunks; ++i) {
          const char* separator = "";
          for (std::size_t k = 0; k < fields().size(); ++k) {
            const int nc = fields().components(k);
            for (int c = 0; c < nc; ++c) {
              if (fields().is_id(k)) fmt::format_to(out, "{}{}", separator, P.ids()[index[i]]);
              else if (!columns[k].empty()) fmt::format_to(out, "{}{}", separator, columns[k][c][index[i]]);
              else fmt::format_to(out, "{}{}", separator, values[k][i * nc + c]);
              separator = " ";
            }
          }
          fmt::format_to(out, "\n");
        }
      }
      for (const auto& part : lines) file.write(part.data(), part.size());
    }
    file.commit();
  }

  // Every rank formats its own particles' lines (in memory order) and the file is written
  // together, in id order (engine/distributed/lines_by_id.hpp): the same bytes as one process's.
  void write_distributed(Simulation& sim, const std::string& path, const fmt::memory_buffer& head) {
    // The ghosts at the current positions first (derived fields read neighbours): rebuilding
    // them later would move the arrays under the columns' pointers.
    sim.refresh_neighbors();
    const auto& P = sim.particles();
    const std::size_t n = P.size(), total = sim.global_count();
    std::vector<std::vector<const real*>> columns(fields().size());
    for (std::size_t k = 0; k < fields().size(); ++k)
      if (!fields().is_id(k)) columns[k] = fields().columns(sim, k);
    std::string first(head.data(), head.size());
    first += fmt::format("{}\n", total);
    fmt::memory_buffer text;
    std::vector<std::size_t> ends(n);
    auto out = std::back_inserter(text);
    for (std::size_t i = 0; i < n; ++i) {
      const char* separator = "";
      for (std::size_t k = 0; k < fields().size(); ++k)
        for (int c = 0; c < fields().components(k); ++c) {
          if (fields().is_id(k)) fmt::format_to(out, "{}{}", separator, P.ids()[i]);
          else fmt::format_to(out, "{}{}", separator, columns[k][static_cast<std::size_t>(c)][i]);
          separator = " ";
        }
      fmt::format_to(out, "\n");
      ends[i] = text.size();
    }
    write_lines_by_id(path, first, P.next_id(), std::span<const std::int64_t>(P.ids(), n),
                      std::span<const char>(text.data(), text.size()), ends);
  }
};

}  // namespace

void register_dump_text(StyleRegistry& r) {
  r.add({"dump/text", StyleKind::fix, "text frames, by default in the original study's format (N, then x y z vx vy vz)",
         Dump::params("out/frame_*.txt", kOriginalFields),
         [](const std::string& id, const Params& p) { return std::make_unique<DumpText>(id, p); }, nullptr});
}

}  // namespace pbf

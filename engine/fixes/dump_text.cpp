// dump/text: the original study's frames, DIR/frame_00000.txt, frame_00001.txt, ...:
// line 1 the particle count N, then N lines "x y z vx vy vz" in input (id) order, each
// number in the shortest form that reads back to the same value. Frame 0 is the state
// when the fix starts; frame k is written at the first step whose time reaches k times the
// interval after that (within a relative 1e-9), or every `every` steps; never twice for one step.
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>

#include "engine/error.hpp"
#include "engine/fixes/styles.hpp"
#include "engine/simulation.hpp"

namespace pbf {

namespace {

class DumpText : public Fix {
 public:
  DumpText(const std::string& id, const Params& p)
      : Fix(id, "dump/text"), dir_(p.string("dir")), interval_(p.real("interval")), every_(p.integer("every")) {
    if (interval_ < 0 || every_ < 0) throw Error("'interval' and 'every' must be >= 0");
    if ((interval_ > 0) == (every_ > 0)) throw Error("give exactly one of 'interval' (seconds) or 'every' (steps)");
    if (dir_.empty()) throw Error("parameter 'dir' must not be empty");
  }

  std::vector<Stage> stages() const override { return {Stage::end_of_step}; }

  void init(Simulation& sim) override {
    std::error_code ec;
    std::filesystem::create_directories(dir_, ec);
    if (!std::filesystem::is_directory(dir_))
      throw Error(fmt::format("cannot create the frame directory '{}'", dir_));
    if (frame_ == 0) start_ = sim.time();  // frames count from when the fix starts
    if (due(sim)) write(sim);
  }

  void end_of_step(Simulation& sim) override {
    if (due(sim)) write(sim);
  }

 private:
  bool due(const Simulation& sim) const {
    if (sim.step() == last_step_) return false;
    if (every_ > 0) return sim.step() % every_ == 0;
    return sim.time() - start_ >= static_cast<double>(frame_) * interval_ * (1 - 1e-9);
  }

  void write(Simulation& sim) {
    const std::string path = fmt::format("{}/frame_{:05d}.txt", dir_, frame_);
    std::FILE* f = std::fopen(path.c_str(), "w");
    if (!f) throw Error(fmt::format("cannot write frame file '{}'", path));
    const auto& P = sim.particles();
    const auto index = P.index_of_id();
    fmt::memory_buffer buf;
    fmt::format_to(std::back_inserter(buf), "{}\n", P.size());
    for (std::uint32_t i : index)
      fmt::format_to(std::back_inserter(buf), "{} {} {} {} {} {}\n", P.x()[i], P.y()[i], P.z()[i], P.vx()[i],
                     P.vy()[i], P.vz()[i]);
    const bool ok = std::fwrite(buf.data(), 1, buf.size(), f) == buf.size();
    if (std::fclose(f) != 0 || !ok) throw Error(fmt::format("cannot write frame file '{}' (disk full?)", path));
    last_step_ = sim.step();
    ++frame_;
  }

  std::string dir_;
  double interval_;
  std::int64_t every_;
  std::int64_t frame_ = 0, last_step_ = -1;
  double start_ = 0;
};

}  // namespace

void register_dump_text(StyleRegistry& r) {
  r.add({"dump/text",
         StyleKind::fix,
         "frames in the original study's text format, DIR/frame_NNNNN.txt",
         {{"dir", ParamType::String, std::string("out"), "", "directory for the frames (created if missing)"},
          {"interval", ParamType::Real, 0.0, "s", "simulated time between frames (or use 'every')"},
          {"every", ParamType::Integer, std::int64_t{0}, "steps", "steps between frames (or use 'interval')"}},
         [](const std::string& id, const Params& p) { return std::make_unique<DumpText>(id, p); }, nullptr});
}

}  // namespace pbf

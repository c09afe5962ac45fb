// dump/movie: the pictures of dump/image piped straight into ffmpeg, which encodes an H.264
// mp4; no frame files on disk. The movie stays open across pbf.run calls and is finished
// when the fix goes (pbf.unfix, or the end of the script). A run continued from a restart
// writes a new movie, so give it another path.
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <sys/wait.h>

#include "engine/core/error.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/io/bytes.hpp"
#include "engine/output/path_pattern.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/render/particle_images.hpp"
#include "engine/output/output_schedule.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

namespace {

bool on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  for (std::size_t start = 0; start <= dirs.size();) {
    const std::size_t end = std::min(dirs.find(':', start), dirs.size());
    const auto candidate = std::filesystem::path(dirs.substr(start, end - start)) / program;
    if (::access(candidate.c_str(), X_OK) == 0) return true;
    start = end + 1;
  }
  return false;
}

// A single-quoted shell word.
std::string shell_quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

class DumpMovie : public Fix {
 public:
  DumpMovie(const std::string& id, const Params& p)
      : Fix(id, "dump/movie"), path_(p.string("path")), fps_(p.integer("fps")), schedule_(p, true), images_(p) {
    if (images_.width() % 2 || images_.height() % 2)
      throw Error("'width' and 'height' must be even (the H.264 encoder's yuv420p needs it)");
    // ffmpeg picks the container from the extension; anything else fails inside ffmpeg.
    const std::string extension = std::filesystem::path(path_).extension().string();
    if (extension != ".mp4" && extension != ".mkv" && extension != ".mov")
      throw Error(fmt::format("parameter 'path' must name an .mp4, .mkv or .mov file, got '{}'", path_));
    if (std::filesystem::is_directory(path_))
      throw Error(fmt::format("parameter 'path': '{}' is a directory", path_));
  }

  ~DumpMovie() override {
    if (!pipe_) return;
    const int status = pclose(pipe_);  // ffmpeg finishes the file when its input ends
    if (status != 0) spdlog::warn("dump/movie '{}': ffmpeg ended with status {}; '{}' may be incomplete", id(), status, path_);
    else spdlog::info("dump/movie '{}': wrote {} ({} frames)", id(), path_, schedule_.count());
  }

  std::vector<Stage> stages() const override { return {Stage::end_of_step}; }
  Role role() const override { return Role::output; }
  bool runs_distributed() const override { return true; }  // the particles gathered on rank 0, its ffmpeg

  void init(Simulation& sim) override {
    images_.init(sim);
    if (!pipe_ && comm::root()) {
      open();
      sim.outputs().wrote(fmt::format("movie of fix '{}' (dump/movie)", id()), path_);
    }
    schedule_.start(sim, fmt::format("fix '{}' ({})", id(), style()));
    end_of_step(sim);
  }

  void end_of_step(Simulation& sim) override {
    if (!schedule_.due(sim)) return;
    const auto& rgb = images_.render(sim);  // every rank: a distributed run gathers on rank 0
    if (pipe_ && std::fwrite(rgb.data(), 1, rgb.size(), pipe_) != rgb.size())
      throw Error(fmt::format("ffmpeg stopped taking frames for '{}' ({}); see its message above", path_,
                              std::strerror(errno)));
    schedule_.done(sim);
  }

  void finish(Simulation&) override {
    if (pipe_) std::fflush(pipe_);
  }

  void save_state(ByteWriter& w) const override { schedule_.save(w); }
  void restore_state(ByteReader& r) override { schedule_.restore(r); }

 private:
  void open() {
    if (!on_path("ffmpeg"))
      throw Error("dump/movie needs ffmpeg on the PATH (Debian: apt-get install ffmpeg); dump/image writes PNGs without it");
    create_parent_directory(path_);
    // A failed write to a dead ffmpeg must be an error we report, not a SIGPIPE that kills us.
    std::signal(SIGPIPE, SIG_IGN);
    const std::string command = fmt::format(
        "ffmpeg -y -loglevel error -f rawvideo -pix_fmt rgb24 -s {}x{} -r {} -i - -c:v libx264 -pix_fmt yuv420p "
        "-crf 18 {}",
        images_.width(), images_.height(), fps_, shell_quoted(path_));
    pipe_ = popen(command.c_str(), "w");
    if (!pipe_) throw Error(fmt::format("cannot start ffmpeg: {}", std::strerror(errno)));
  }

  std::string path_;
  std::int64_t fps_;
  OutputSchedule schedule_;
  ParticleImages images_;
  std::FILE* pipe_ = nullptr;
};

}  // namespace

void register_dump_movie(StyleRegistry& r) {
  std::vector<ParamSpec> params = {
      {"path", ParamType::String, std::string("out/movie.mp4"), "", "the movie file (H.264 mp4)"},
      ParamSpec{"fps", ParamType::Integer, std::int64_t{25}, "1/s", "frames per second of the movie"}.within(1, 240)};
  for (auto& p : OutputSchedule::params("frames")) params.push_back(std::move(p));
  for (auto& p : ParticleImages::params()) params.push_back(std::move(p));
  r.add({"dump/movie", StyleKind::fix, "an mp4 movie of the pictures dump/image draws, encoded by ffmpeg as the run goes",
         std::move(params), [](const std::string& id, const Params& p) { return std::make_unique<DumpMovie>(id, p); },
         nullptr});
}

}  // namespace pbf

// view: the run, live in a web browser (docs/view.md). Rank 0 serves a page on this machine
// (engine/view/view_server.hpp) that shows the particles in 3D coloured by a field, the solids,
// the thermo columns as plots, the log, and the run's pace; from it a person pauses, steps,
// resumes or stops the run (with a restart, as Ctrl-C) and takes a picture with dump/image's
// renderer from the browser's camera.
//
// The fix joins no stage: the run loop asks it after every step what the viewers wish
// (engine/core/run_view.hpp), agrees that over the ranks with Ctrl-C's reduction, and then
// every rank gathers a frame when one is wished. A frame is wished only when a viewer has
// taken the last one and the gathers so far cost at most ViewServer::kFrameBudget of the run,
// so the run pays for no more frames than a browser draws.
#include <cmath>
#include <cstring>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <omp.h>
#include <spdlog/sinks/base_sink.h>
#include <spdlog/spdlog.h>
#include <thread>
#include <unistd.h>

#include "engine/core/interrupt.hpp"
#include "engine/core/run_view.hpp"
#include "engine/core/simulation.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/geometry/solid_body.hpp"
#include "engine/output/dump_fields.hpp"
#include "engine/output/path_pattern.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/render/particle_images.hpp"
#include "engine/view/view_frame.hpp"
#include "engine/view/view_server.hpp"

namespace pbf {

namespace {

using nlohmann::json;

// The fields a viewer may colour by, where the pipeline has them.
const char* const kColourFields[] = {"speed", "density", "density_error", "pressure", "vorticity_magnitude", "id"};

// The log, line by line, to the viewers as well.
class ViewLogSink : public spdlog::sinks::base_sink<std::mutex> {
 public:
  explicit ViewLogSink(ViewServer& server) : server_(server) {}

 protected:
  void sink_it_(const spdlog::details::log_msg& msg) override {
    const std::string text(msg.payload.data(), msg.payload.size());
    const std::string level(spdlog::level::to_string_view(msg.level).data(),
                            spdlog::level::to_string_view(msg.level).size());
    std::size_t start = 0;
    while (start <= text.size()) {
      const std::size_t end = std::min(text.find('\n', start), text.size());
      server_.publish_log(fmt::format("[{}] {}", level, text.substr(start, end - start)));
      start = end + 1;
    }
  }
  void flush_() override {}

 private:
  ViewServer& server_;
};

class View : public Fix, public RunView {
 public:
  View(const std::string& id, const Params& p)
      : Fix(id, "view"),
        colour_(p.string("color")),
        pictures_(p.string("pictures"), "step number"),
        most_points_(p.integer("points")) {
    // Rank 0 serves; the others learn whether it could, so that all fail together.
    std::string failure;
    if (comm::root()) {
      try {
        server_ = std::make_unique<ViewServer>(ViewServer::Options{
            p.string("address"), static_cast<int>(p.integer("port")), p.boolean("allow_remote")});
      } catch (const Error& e) {
        failure = e.what();
      }
    }
    if (comm::max(failure.empty() ? 0.0 : 1.0) > 0)
      throw Error(comm::root() ? failure : "view: rank 0 could not serve the view (its message says why)");
    title_ = p.string("title");
    if (server_) {
      spdlog::info("view: watch this run at {}", server_->url());
      char host[256] = "THIS_MACHINE";
      gethostname(host, sizeof host - 1);
      spdlog::info("view: from another machine, tunnel first (ssh -N -L {0}:127.0.0.1:{0} {1}), then open the same "
                   "address there",
                   server_->port(), host);
      sink_ = std::make_shared<ViewLogSink>(*server_);
      spdlog::default_logger()->sinks().push_back(sink_);
    }
  }

  ~View() override {
    if (sink_) {
      auto& sinks = spdlog::default_logger()->sinks();
      sinks.erase(std::remove(sinks.begin(), sinks.end(), sink_), sinks.end());
    }
  }

  std::vector<Stage> stages() const override { return {}; }
  Role role() const override { return Role::output; }
  bool runs_distributed() const override { return true; }
  std::vector<const char*> exclusive_jobs() const override { return {"live view"}; }
  RunView* run_view() override { return this; }
  bool in_restarts() const override { return false; }

  void init(Simulation& sim) override {
    const std::vector<std::string> valid = DumpFields::valid_names(sim);
    fields_.clear();
    for (const char* name : kColourFields)
      if (std::find(valid.begin(), valid.end(), name) != valid.end()) fields_.emplace_back(name);
    if (std::find(valid.begin(), valid.end(), colour_) == valid.end())
      throw Error(fmt::format("'color': no field '{}' (one of {})", colour_, fmt::join(valid, ", ")));
    if (std::find(fields_.begin(), fields_.end(), colour_) == fields_.end()) fields_.insert(fields_.begin(), colour_);
    frame_.choose(sim, colour_);
  }

  void run_starts(Simulation& sim, std::int64_t last_step, double end_time) override {
    first_step_ = sim.step(), last_step_ = last_step, end_time_ = end_time;
    held_ = false, thermo_lines_ = sim.thermo().lines_output();  // its lines from here on
    step_ = sim.step(), frame_step_ = -2;
    solids_version_ = ~std::uint64_t{0};
    rate_step_ = sim.step(), rate_clock_ = omp_get_wtime(), rate_time_ = sim.time();
    steps_per_second_ = 0, sim_seconds_per_second_ = 0;
    const double spacing = ViewFrame::spacing(sim);  // collective
    if (!server_) return;
    const Domain& d = sim.domain();
    json columns = json::array();
    const auto units = sim.thermo().units(sim);
    for (std::size_t k = 0; k < sim.thermo().columns().size(); ++k)
      columns.push_back({{"name", sim.thermo().columns()[k]}, {"unit", k < units.size() ? units[k] : "-"}});
    server_->publish_hello({{"title", title_},
                            {"particles", sim.global_count()},
                            {"fields", fields_},
                            {"color", colour_},
                            {"domain", {{"lo", {d.lo[0], d.lo[1], d.lo[2]}}, {"hi", {d.hi[0], d.hi[1], d.hi[2]}}}},
                            {"spacing", spacing},
                            {"columns", columns},
                            {"state", "running"},
                            {"plan", {{"first_step", first_step_},
                                      {"last_step", last_step_ >= 0 ? json(last_step_) : json(nullptr)},
                                      {"end_time", last_step_ < 0 ? json(end_time_) : json(nullptr)}}}});
    publish_status(sim, "running", true);
  }

  ViewWishes wishes() override {
    ViewWishes w;
    if (!server_) return w;
    ViewServer::Commands c = server_->take_commands();
    if (c.stop) InterruptWatch::request_stop("stopped from the live view");
    const auto chosen = std::find(fields_.begin(), fields_.end(), c.field);
    if (!c.field.empty() && chosen != fields_.end()) w.field = 1.0 + static_cast<double>(chosen - fields_.begin());
    if (c.picture) picture_request_ = json::parse(*c.picture), w.picture = 1;
    w.pause = c.pause ? 1 : 0;
    w.step = c.step ? 1 : 0;
    // A held run sends no frame twice (a gather under MPI), only one in a new colour.
    w.frame = (server_->frame_wanted() && step_ != frame_step_) || w.field > 0 ? 1 : 0;
    return w;
  }

  void act(Simulation& sim, const ViewWishes& agreed, bool held) override {
    step_ = sim.step();
    if (agreed.field > 0) {
      colour_ = fields_.at(static_cast<std::size_t>(agreed.field) - 1);
      frame_.choose(sim, colour_);
    }
    if (agreed.frame > 0) send_frame(sim);
    if (agreed.picture > 0) take_picture(sim);
    if (!server_) return;
    if (sim.thermo().lines_output() != thermo_lines_) {
      thermo_lines_ = sim.thermo().lines_output();
      server_->publish_thermo({{"step", sim.thermo().last_line_step()}, {"values", sim.thermo().last_line()}});
    }
    publish_status(sim, held ? "paused" : "running", held != held_);
    held_ = held;
  }

  void run_ends(Simulation& sim, const std::string& state, const std::string& message) override {
    if (!server_) return;
    publish_status(sim, state, true, message);
  }

  int port() const override { return server_ ? server_->port() : 0; }

  void wait(double seconds) override {
    if (server_) server_->wait_for_command(seconds);
    else std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
  }

 private:
  // Collective: every rank's particles to rank 0, which publishes them.
  void send_frame(Simulation& sim) {
    const double start = omp_get_wtime();
    std::shared_ptr<const std::string> bytes = frame_.gather(sim, ++frame_seq_, most_points_);
    frame_step_ = sim.step();
    if (!server_) return;
    std::uint64_t version = 0;
    for (const SolidBody* s : sim.solid_bodies()) version = version * 1000003 + s->surface_version() + 1;
    if (version != solids_version_) {
      solids_version_ = version;
      server_->publish_solids(solids_json(sim, version));
    }
    server_->publish_frame({{"seq", frame_seq_},
                            {"step", sim.step()},
                            {"time", sim.time()},
                            {"count", frame_.count()},
                            {"stride", frame_.stride()},
                            {"color", colour_},
                            {"unit", frame_.unit()},
                            {"min", frame_.low()},
                            {"max", frame_.high()},
                            {"solids_version", solids_version_}},
                           std::move(bytes), omp_get_wtime() - start);
  }

  static json solids_json(const Simulation& sim, std::uint64_t version) {
    json solids = json::array();
    for (const SolidBody* s : sim.solid_bodies()) {
      const TriangleMesh& mesh = s->surface();
      std::vector<float> vertices;
      std::vector<std::uint32_t> triangles;
      for (const auto& v : mesh.vertices) vertices.insert(vertices.end(), {float(v[0]), float(v[1]), float(v[2])});
      for (const auto& t : mesh.triangles) triangles.insert(triangles.end(), t.begin(), t.end());
      solids.push_back({{"name", s->name()}, {"container", s->fluid_inside()}, {"vertices", vertices},
                        {"triangles", triangles}});
    }
    return {{"version", version}, {"solids", solids}};
  }

  // Collective like a frame: dump/image's renderer, from the viewer's camera (on rank 0).
  void take_picture(Simulation& sim) {
    const json& r = picture_request_;
    GivenParams given = {{"color", colour_}, {"axes", true}};
    if (server_) {
      const double fov = r["fov"].get<double>() * M_PI / 180;
      given.push_back({"position", vec(r["position"])});
      given.push_back({"center", vec(r["target"])});
      given.push_back({"up", vec(r["up"])});
      given.push_back({"zoom", std::tan(0.5 * 30 * M_PI / 180) / std::tan(0.5 * fov)});  // dump/image's 30 degrees
      given.push_back({"width", std::int64_t{r["width"].get<int>()}});
      given.push_back({"height", std::int64_t{r["height"].get<int>()}});
    }
    std::string failure, path;
    std::optional<ParticleImages> images;
    try {
      images.emplace(Params("view picture", ParticleImages::params(), given));
    } catch (const Error& e) {
      failure = e.what();  // rank 0's camera
    }
    if (comm::max(failure.empty() ? 0.0 : 1.0) > 0) images.reset();  // all ranks render, or none
    try {
      if (!images) throw Error(failure);
      images->init(sim);
      const auto& rgb = images->render(sim);  // every rank: gathered on rank 0
      if (server_) {
        path = pictures_.with(fmt::format("{:08d}", sim.step()));
        pictures_.create_directory();
        write_png(path, images->width(), images->height(), rgb);
      }
    } catch (const Error& e) {
      failure = e.what();  // rank 0's camera (the others render nothing)
    }
    if (!server_) return;
    if (failure.empty()) {
      spdlog::info("view: wrote picture '{}' (step {})", path, sim.step());
      server_->publish_picture({{"path", path}, {"step", sim.step()}});
    } else {
      spdlog::warn("view: picture: {}", failure);
      server_->publish_picture({{"error", failure}});
    }
  }

  static Vec3 vec(const json& a) { return {a[0].get<double>(), a[1].get<double>(), a[2].get<double>()}; }

  // About twice a second, and at once when the state changes. The pace is measured over the
  // last half second of running (a held run has none), the time left from it.
  void publish_status(Simulation& sim, const std::string& state, bool now, const std::string& message = "") {
    const double t = omp_get_wtime();
    if (!now && t - status_at_ < 0.5) return;
    status_at_ = t;
    if (state == "running" && held_) {  // resumed: the pace starts again
      rate_step_ = sim.step(), rate_clock_ = t, rate_time_ = sim.time();
    } else if (state == "running" && t - rate_clock_ >= 0.5) {
      steps_per_second_ = static_cast<double>(sim.step() - rate_step_) / (t - rate_clock_);
      sim_seconds_per_second_ = (sim.time() - rate_time_) / (t - rate_clock_);
      rate_step_ = sim.step(), rate_clock_ = t, rate_time_ = sim.time();
    }
    json left = nullptr;
    if (state == "running" && last_step_ >= 0 && steps_per_second_ > 0)
      left = static_cast<double>(last_step_ - sim.step()) / steps_per_second_;
    else if (state == "running" && last_step_ < 0 && sim_seconds_per_second_ > 0)
      left = std::max(0.0, end_time_ - sim.time()) / sim_seconds_per_second_;
    json status = {{"step", sim.step()},
                   {"time", sim.time()},
                   {"steps_per_second", state == "running" ? steps_per_second_ : 0.0},
                   {"seconds_left", left},
                   {"state", state},
                   {"particles", sim.global_count()}};
    if (!message.empty()) status["message"] = message;
    server_->publish_status(status);
  }

  std::string colour_, title_;
  PathPattern pictures_;
  std::int64_t most_points_;
  std::unique_ptr<ViewServer> server_;  // rank 0's
  std::shared_ptr<ViewLogSink> sink_;
  std::vector<std::string> fields_;
  ViewFrame frame_;
  json picture_request_;
  std::uint64_t frame_seq_ = 0, solids_version_ = 0;
  std::int64_t first_step_ = 0, last_step_ = -1, thermo_lines_ = 0;
  std::int64_t step_ = -1, frame_step_ = -2;  // the step now, and of the last frame sent
  double end_time_ = 0, status_at_ = -1e9;
  std::int64_t rate_step_ = 0;
  double rate_clock_ = 0, rate_time_ = 0, steps_per_second_ = 0, sim_seconds_per_second_ = 0;
  bool held_ = false;
};

}  // namespace

void register_view(StyleRegistry& r) {
  r.add({"view", StyleKind::fix,
         "the run live in a web browser: particles, solids, thermo plots and log; pause, step, stop, pictures",
         {ParamSpec{"port", ParamType::Integer, std::int64_t{0}, "",
                    "TCP port to serve on (0: a free one, printed with the address)"}
              .within(0, 65535),
          {"address", ParamType::String, std::string("127.0.0.1"), "",
           "address to serve on: this machine's loopback unless allow_remote (reach it through an ssh tunnel)"},
          {"allow_remote", ParamType::Bool, false, "",
           "allow an address other than the loopback (anyone who can reach it and has the token can stop the run)"},
          {"color", ParamType::String, std::string("speed"), "", "the colour field the view starts with"},
          {"title", ParamType::String, std::string(""), "", "what the page's title says (the command line: the script)"},
          {"pictures", ParamType::String, std::string("out/view_*.png"), "",
           "where the viewer's pictures go ('*': the step)"},
          ParamSpec{"points", ParamType::Integer, std::int64_t{2000000}, "",
                    "the most particles a frame carries: beyond, one in k by id (the same ones every frame)"}
              .within(1000, 1e9)},
         [](const std::string& id, const Params& p) { return std::make_unique<View>(id, p); }, nullptr});
}

}  // namespace pbf

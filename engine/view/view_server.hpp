#pragma once
// The live view's web server (docs/view.md): serves the page, its scripts and the run's
// frames, thermo rows, log and state to browsers on this machine, and takes their commands.
// cpp-httplib (Debian's libcpp-httplib-dev) answers on its own threads; the run loop only
// publishes into memory under a mutex and reads the commands, so a slow or vanished browser
// never stops or slows a step. Only rank 0 of a distributed run has one.
//
// Who may talk to it: the printed address carries the user's random token (kept readable by
// the user alone, so that a continued run takes the same), required on every request for data
// or control; the Host header must name the loopback (no DNS rebinding) and an Origin header,
// when sent, this page (no other page in the browser may post commands).
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace httplib {
class Server;
struct Request;
struct Response;
}  // namespace httplib

namespace pbf {

class ViewServer {
 public:
  struct Options {
    std::string address = "127.0.0.1";
    int port = 0;               // 0: a free port
    bool allow_remote = false;  // serve on an address other than the loopback
  };
  // Checks the options and binds the port (pbf::Error naming the problem), then serves.
  explicit ViewServer(const Options& options);
  ~ViewServer();
  ViewServer(const ViewServer&) = delete;
  ViewServer& operator=(const ViewServer&) = delete;

  int port() const { return port_; }
  // The address to open, with its token.
  std::string url() const;
  const std::string& token() const { return token_; }

  // --- what the run publishes (the run loop's thread; the log from any thread) ---
  // (The events' contents are in docs/design.md#the-live-view.)
  void publish_hello(const nlohmann::json& hello);  // a run starts: fields, columns, plan
  void publish_thermo(const nlohmann::json& row);   // one thermo row
  void publish_log(const std::string& line);
  void publish_status(const nlohmann::json& status);
  // A frame: its event (with its "seq") and its bytes (GET /frame); `seconds` is what gathering
  // it cost the run, which keeps frames rare enough to cost at most kFrameBudget of its time.
  void publish_frame(const nlohmann::json& frame, std::shared_ptr<const std::string> bytes, double seconds);
  void publish_solids(const nlohmann::json& solids);  // GET /solids
  void publish_picture(const nlohmann::json& picture);

  // --- what the viewers ask for (read by the run loop) ---
  // Whether a frame is wanted now: a viewer watches, has taken the last frame (or has had a
  // second to), and enough time has passed since it.
  bool frame_wanted() const;
  struct Commands {
    bool pause = false;  // the run is to be held (stays until resumed)
    bool step = false;   // one more step (taken by this call)
    bool stop = false;   // stop with a restart (taken)
    std::string field;   // a colour field chosen since the last call ("" none; taken)
    std::optional<std::string> picture;  // a picture's request, JSON (taken)
  };
  Commands take_commands();
  // Waits up to `seconds` for a command.
  void wait_for_command(double seconds);
  int viewers() const { return viewers_.load(); }

  static constexpr double kFrameBudget = 0.02;  // of the run's time, at most
  static constexpr double kMostFramesPerSecond = 20;

 private:
  struct Event {
    std::uint64_t id;
    std::string text;  // "event: NAME\ndata: JSON\n\n"
  };
  void route();
  bool allowed(const httplib::Request& req, httplib::Response& res) const;
  void serve_events(const httplib::Request& req, httplib::Response& res);
  void control(const httplib::Request& req, httplib::Response& res);
  void push(const char* name, const nlohmann::json& data);  // holding mutex_
  std::string replay() const;                             // holding mutex_

  Options options_;
  int port_ = 0;
  std::string token_, run_id_;
  std::unique_ptr<httplib::Server> server_;
  std::thread thread_;
  std::atomic<bool> listen_ended_{false};

  mutable std::mutex mutex_;
  std::condition_variable changed_;  // an event, a command, the end
  bool stopping_ = false;
  std::deque<Event> events_;  // the newest, for streams catching up
  std::uint64_t next_event_ = 1;
  std::string hello_, status_, frame_event_, solids_;  // the latest, as sent
  std::vector<std::string> fields_;  // the colour fields hello offered
  std::vector<std::string> thermo_rows_;  // of this run, replayed to a new viewer
  std::deque<std::string> log_lines_;     // the newest, replayed likewise
  std::shared_ptr<const std::string> frame_;
  std::uint64_t frame_seq_ = 0, frame_taken_ = 0;
  double frame_sent_at_ = -1e9, frame_interval_ = 1 / kMostFramesPerSecond;
  Commands commands_;
  std::atomic<int> viewers_{0};
};

}  // namespace pbf

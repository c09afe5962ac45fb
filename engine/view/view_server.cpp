// The live view's web server (engine/view/view_server.hpp): routes, the checks every request
// passes, the event stream, and the commands.
#include "engine/view/view_server.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <fmt/format.h>
#include <httplib.h>
#include <netdb.h>
#include <nlohmann/json.hpp>
#include <random>
#include <sys/socket.h>
#include <unistd.h>

#include "engine/core/error.hpp"
#include "engine/view/view_assets.hpp"

namespace pbf {

namespace {

using nlohmann::json;

constexpr std::size_t kEventsKept = 4096, kLogLinesReplayed = 500, kThermoRowsKept = 100000;

double clock_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::string random_hex(int bytes) {
  std::random_device device;  // the kernel's random numbers
  std::string hex;
  for (int i = 0; i < bytes; ++i) hex += fmt::format("{:02x}", device() & 0xff);
  return hex;
}

bool is_loopback(const std::string& address) {
  return address == "localhost" || address == "::1" || address.rfind("127.", 0) == 0;
}

// A Host header naming this machine's loopback, with any port (a tunnel may forward another
// local port to this one); a name that only resolves to it (DNS rebinding) is refused.
bool loopback_host(const std::string& host) {
  for (const char* name : {"127.0.0.1:", "localhost:", "[::1]:"}) {
    const std::size_t n = std::strlen(name);
    if (host.size() > n && host.compare(0, n, name) == 0 &&
        host.find_first_not_of("0123456789", n) == std::string::npos)
      return true;
  }
  return false;
}

// Binds a socket where the server will, to say why it cannot (cpp-httplib only says false).
void check_port(const std::string& address, int port) {
  addrinfo hints{}, *found = nullptr;
  hints.ai_socktype = SOCK_STREAM;
  // Numbers only (and "localhost"): a name would mean a DNS query, which may hang.
  hints.ai_flags = AI_PASSIVE | AI_NUMERICSERV | (address == "localhost" ? 0 : AI_NUMERICHOST);
  if (const int e = getaddrinfo(address.c_str(), std::to_string(port).c_str(), &hints, &found); e != 0)
    throw Error(fmt::format("cannot use the address '{}' ({}): give a numeric address such as 127.0.0.1",
                            address, gai_strerror(e)));
  const int fd = socket(found->ai_family, found->ai_socktype, found->ai_protocol);
  const int yes = 1;
  setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);  // as the server will
  const int bound = fd >= 0 ? bind(fd, found->ai_addr, found->ai_addrlen) : -1;
  const int error = errno;
  if (fd >= 0) close(fd);
  freeaddrinfo(found);
  if (bound == 0) return;
  if (error == EADDRINUSE)
    throw Error(fmt::format("port {} is in use (another run's view?): choose another, or 0 for a free one", port));
  if (error == EACCES)
    throw Error(fmt::format("port {} needs root's rights (ports below 1024): choose one from 1024 to 65535, "
                            "or 0 for a free one",
                            port));
  if (error == EADDRNOTAVAIL) throw Error(fmt::format("'{}' is not an address of this machine", address));
  throw Error(fmt::format("cannot serve on {} port {}: {}", address, port, std::strerror(error)));
}

// The user's token, kept in ~/.config/pbfengine/view-token (readable by the user alone) and
// made there the first time: the continuation of a stopped run serves with the same one, so
// the page still open reconnects to it. Where no such file can be kept, one for this run.
std::string user_token() {
  const char* config = std::getenv("XDG_CONFIG_HOME");
  const char* home = std::getenv("HOME");
  if ((!config || !*config) && (!home || !*home)) return random_hex(16);
  const std::filesystem::path dir =
      config && *config ? std::filesystem::path(config) / "pbfengine" : std::filesystem::path(home) / ".config/pbfengine";
  const std::filesystem::path path = dir / "view-token";
  auto read = [&]() -> std::string {
    std::ifstream in(path);
    std::string token;
    in >> token;
    const bool hex = token.size() == 32 && token.find_first_not_of("0123456789abcdef") == std::string::npos;
    return hex ? token : "";
  };
  if (std::string token = read(); !token.empty()) return token;
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  // Written whole under another name, then renamed: two runs starting at once agree on one.
  const std::string token = random_hex(16);
  const std::filesystem::path temporary = dir / fmt::format("view-token.{}", getpid());
  const int fd = open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  if (fd < 0) return token;
  const bool written = write(fd, token.data(), token.size()) == static_cast<ssize_t>(token.size());
  close(fd);
  if (written) link(temporary.c_str(), path.c_str());  // fails if another run made it first
  unlink(temporary.c_str());
  const std::string kept = read();
  return kept.empty() ? token : kept;
}

// Equal strings, in a time that does not tell how much of a guess was right.
bool same_secret(const std::string& a, const std::string& b) {
  if (a.size() != b.size()) return false;
  unsigned char differ = 0;
  for (std::size_t i = 0; i < a.size(); ++i) differ |= static_cast<unsigned char>(a[i] ^ b[i]);
  return differ == 0;
}

std::string event_text(const char* name, const json& data) {
  return fmt::format("event: {}\ndata: {}\n\n", name, data.dump(-1, ' ', false, json::error_handler_t::replace));
}

void refuse(httplib::Response& res, int status, const std::string& message) {
  res.status = status;
  res.set_content(json{{"error", message}}.dump(-1, ' ', false, json::error_handler_t::replace), "application/json");
}

// A vector of three finite numbers, or an error naming it.
std::array<double, 3> vector3(const json& camera, const char* name) {
  const auto it = camera.find(name);
  if (it == camera.end() || !it->is_array() || it->size() != 3)
    throw Error(fmt::format("picture: camera.{} must be three numbers", name));
  std::array<double, 3> v{};
  for (int k = 0; k < 3; ++k) {
    if (!(*it)[k].is_number() || !std::isfinite((*it)[k].get<double>()))
      throw Error(fmt::format("picture: camera.{} must be three finite numbers", name));
    v[k] = (*it)[k].get<double>();
  }
  return v;
}

// The picture's request with its values checked (the engine's renderer checks the geometry).
json checked_picture(const json& request) {
  const auto camera = request.find("camera");
  if (camera == request.end() || !camera->is_object()) throw Error("picture: 'camera' must be an object");
  json out = {{"position", vector3(*camera, "position")},
              {"target", vector3(*camera, "target")},
              {"up", vector3(*camera, "up")}};
  const auto fov = camera->find("fov");
  if (fov == camera->end() || !fov->is_number() || !(fov->get<double>() >= 1 && fov->get<double>() <= 170))
    throw Error("picture: camera.fov must be a number of degrees from 1 to 170");
  out["fov"] = fov->get<double>();
  for (const char* side : {"width", "height"}) {
    const auto it = request.find(side);
    const double v = it != request.end() && it->is_number() ? it->get<double>() : 0;
    if (!(v >= 16 && v <= 8192)) throw Error(fmt::format("picture: '{}' must be 16 to 8192 pixels", side));
    out[side] = static_cast<int>(v);
  }
  return out;
}

}  // namespace

ViewServer::ViewServer(const Options& options) : options_(options) {
  if (options.port < 0 || options.port > 65535)
    throw Error(fmt::format("port {} is out of range: give 1024 to 65535, or 0 for a free one", options.port));
  if (!is_loopback(options.address) && !options.allow_remote)
    throw Error(fmt::format("'{}' is not this machine's loopback address: anyone who can reach it could watch "
                            "(and stop) the run. Serve on 127.0.0.1 and reach it through an ssh tunnel "
                            "(docs/view.md), or allow it explicitly (allow_remote = true, --view-allow-remote)",
                            options.address));
  check_port(options.address, options.port);
  token_ = user_token();
  run_id_ = random_hex(8);

  server_ = std::make_unique<httplib::Server>();
  server_->new_task_queue = [] { return new httplib::ThreadPool(16); };  // a stream holds a thread
  // SO_REUSEADDR, as check_port binds: the continuation of a stopped run serves on the same
  // port while the last run's connections linger (TIME_WAIT). (cpp-httplib's default,
  // SO_REUSEPORT, would also let two runs listen on one port.)
  server_->set_socket_options([](socket_t sock) {
    const int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  // Short: the run's end waits for the server's threads, each until its connection's timeout
  // (an idle keep-alive, a request half sent, a stream nobody reads).
  server_->set_read_timeout(2, 0);
  server_->set_write_timeout(1, 0);  // a socket that takes nothing for a second: the viewer is gone
  server_->set_keep_alive_timeout(1);
  server_->set_payload_max_length(1 << 16);  // a command is a few hundred bytes
  route();
  port_ = options.port == 0 ? server_->bind_to_any_port(options.address) : options.port;
  if (port_ <= 0 || (options.port != 0 && !server_->bind_to_port(options.address, options.port)))
    throw Error(fmt::format("cannot serve on {} port {}", options.address, options.port));
  thread_ = std::thread([this] {
    server_->listen_after_bind();
    listen_ended_ = true;
  });
  // A stop before the server listens would be lost (cpp-httplib), and a run of a few steps
  // would then wait for ever at its end.
  while (!server_->is_running() && !listen_ended_) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  if (!server_->is_running()) {
    thread_.join();
    throw Error(fmt::format("cannot serve on {} port {}", options.address, port_));
  }
}

ViewServer::~ViewServer() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();  // the streams end
  server_->stop();
  if (thread_.joinable()) thread_.join();
}

std::string ViewServer::url() const {
  std::string host = options_.address;
  if (host.find(':') != std::string::npos) host = "[" + host + "]";
  return fmt::format("http://{}:{}/?token={}", host, port_, token_);
}

// Every request: a Host that names this server, no other page's Origin, and the token on all
// but the page's own static files.
bool ViewServer::allowed(const httplib::Request& req, httplib::Response& res) const {
  const std::string host = req.get_header_value("Host");
  const bool host_ok = options_.allow_remote ? !host.empty() : loopback_host(host);
  if (!host_ok) {
    refuse(res, 403, fmt::format("this view answers to 127.0.0.1, localhost or [::1] only (the request named "
                                   "'{}')",
                                   host));
    return false;
  }
  const std::string origin = req.get_header_value("Origin");
  if (!origin.empty() && origin != "http://" + host) {
    refuse(res, 403, "requests from other pages are refused");
    return false;
  }
  static const char* const kPublic[] = {"/view.js", "/view.css", "/three.min.js", "/OrbitControls.js"};
  if (std::find_if(std::begin(kPublic), std::end(kPublic), [&](const char* p) { return req.path == p; }) !=
      std::end(kPublic))
    return true;
  if (!same_secret(req.get_param_value("token"), token_)) {
    refuse(res, 403,
           "this view needs the address the run printed, with its token (http://127.0.0.1:PORT/?token=...)");
    return false;
  }
  return true;
}

void ViewServer::route() {
  auto& s = *server_;
  s.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
    return allowed(req, res) ? httplib::Server::HandlerResponse::Unhandled : httplib::Server::HandlerResponse::Handled;
  });
  s.set_post_routing_handler([](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-store");
    res.set_header("Referrer-Policy", "no-referrer");  // the token is in the address
    res.set_header("X-Content-Type-Options", "nosniff");
    res.set_header("Content-Security-Policy",
                   "default-src 'self'; style-src 'self' 'unsafe-inline'; img-src 'self' data:; frame-ancestors 'none'");
  });
  for (const ViewAsset& asset : view_assets()) {
    auto serve = [&asset](const httplib::Request&, httplib::Response& res) {
      res.set_content(reinterpret_cast<const char*>(asset.data), asset.size, asset.type);
    };
    s.Get(asset.path, serve);
    if (std::strcmp(asset.path, "/index.html") == 0) s.Get("/", serve);
  }
  s.Get("/events", [this](const httplib::Request& req, httplib::Response& res) { serve_events(req, res); });
  s.Get("/frame", [this](const httplib::Request&, httplib::Response& res) {
    std::shared_ptr<const std::string> frame;
    {
      std::lock_guard lock(mutex_);
      frame = frame_;
      frame_taken_ = frame_seq_;
    }
    if (!frame) return refuse(res, 404, "no frame yet");
    res.set_content(frame->data(), frame->size(), "application/octet-stream");
  });
  s.Get("/solids", [this](const httplib::Request&, httplib::Response& res) {
    std::lock_guard lock(mutex_);
    res.set_content(solids_.empty() ? std::string(R"({"version":0,"solids":[]})") : solids_, "application/json");
  });
  s.Post("/control", [this](const httplib::Request& req, httplib::Response& res) { control(req, res); });
}

// Server-sent events: what a new viewer needs (the run's description, its thermo rows so
// far, the newest log lines, the state, the newest frame), then every event as it comes.
void ViewServer::serve_events(const httplib::Request&, httplib::Response& res) {
  std::string first;
  std::uint64_t cursor;
  {
    std::lock_guard lock(mutex_);
    first = replay();
    cursor = next_event_;
  }
  ++viewers_;
  res.set_chunked_content_provider(
      "text/event-stream",
      [this, first = std::move(first), cursor](std::size_t, httplib::DataSink& sink) mutable {
        if (!first.empty()) {
          const bool ok = sink.write(first.data(), first.size());
          first.clear();
          return ok;
        }
        std::string out;
        bool ending;
        {
          std::unique_lock lock(mutex_);
          changed_.wait_for(lock, std::chrono::seconds(15), [&] { return stopping_ || next_event_ > cursor; });
          // A stream that fell behind the events kept goes on from the oldest.
          for (const Event& e : events_)
            if (e.id >= cursor) out += e.text;
          cursor = next_event_;
          ending = stopping_;
        }
        if (ending) {  // the run's last events (its end), then the stream ends
          if (!out.empty()) sink.write(out.data(), out.size());
          return false;
        }
        if (out.empty()) out = ": keep-alive\n\n";
        return sink.write(out.data(), out.size());
      },
      [this](bool) { --viewers_; });
}

std::string ViewServer::replay() const {
  std::string out = hello_;
  for (const std::string& row : thermo_rows_) out += row;
  if (!log_lines_.empty()) out += event_text("log", json{{"lines", log_lines_}});
  return out + status_ + frame_event_;
}

void ViewServer::control(const httplib::Request& req, httplib::Response& res) {
  if (req.get_header_value("Content-Type").rfind("application/json", 0) != 0)
    return refuse(res, 415, "commands are JSON (Content-Type: application/json)");
  json command;
  try {
    command = json::parse(req.body);
  } catch (const json::exception&) {
    return refuse(res, 400, "the command is not JSON");
  }
  if (!command.is_object() || !command.contains("command") || !command["command"].is_string())
    return refuse(res, 400, "a command is {\"command\": NAME, ...}");
  const std::string name = command["command"];
  {
    std::lock_guard lock(mutex_);
    if (name == "pause") {
      commands_.pause = true;
    } else if (name == "resume") {
      commands_.pause = false;
    } else if (name == "step") {
      commands_.pause = true, commands_.step = true;
    } else if (name == "stop") {
      commands_.stop = true;
    } else if (name == "color") {
      const std::string field = command.value("field", std::string());
      if (std::find(fields_.begin(), fields_.end(), field) == fields_.end())
        return refuse(res, 400, fmt::format("no colour field '{}' (the run offers {})", field, json(fields_).dump()));
      commands_.field = field;
    } else if (name == "picture") {
      try {
        commands_.picture = checked_picture(command).dump();
      } catch (const Error& e) {
        return refuse(res, 400, e.what());
      }
    } else {
      return refuse(res, 400, fmt::format("unknown command '{}' (pause, resume, step, stop, color, picture)", name));
    }
  }
  changed_.notify_all();
  res.set_content(R"({"ok":true})", "application/json");
}

void ViewServer::push(const char* name, const json& data) {
  events_.push_back({next_event_++, event_text(name, data)});
  if (events_.size() > kEventsKept) events_.pop_front();
  changed_.notify_all();
}

void ViewServer::publish_hello(const json& hello) {
  json h = hello;
  h["run_id"] = run_id_;
  std::lock_guard lock(mutex_);
  hello_ = event_text("hello", h);
  fields_ = h.value("fields", std::vector<std::string>{});
  thermo_rows_.clear();
  frame_event_.clear();
  push("hello", h);
}

void ViewServer::publish_thermo(const json& row) {
  std::lock_guard lock(mutex_);
  if (thermo_rows_.size() < kThermoRowsKept) thermo_rows_.push_back(event_text("thermo", row));
  push("thermo", row);
}

void ViewServer::publish_log(const std::string& line) {
  std::lock_guard lock(mutex_);
  log_lines_.push_back(line);
  if (log_lines_.size() > kLogLinesReplayed) log_lines_.pop_front();
  push("log", json{{"lines", {line}}});
}

void ViewServer::publish_status(const json& status) {
  std::lock_guard lock(mutex_);
  status_ = event_text("status", status);
  push("status", status);
}

void ViewServer::publish_frame(const json& frame, std::shared_ptr<const std::string> bytes, double seconds) {
  std::lock_guard lock(mutex_);
  frame_ = std::move(bytes);
  frame_seq_ = frame.value("seq", std::uint64_t{0});
  frame_sent_at_ = clock_seconds();
  frame_interval_ = std::max(1 / kMostFramesPerSecond, seconds / kFrameBudget);
  frame_event_ = event_text("frame", frame);
  push("frame", frame);
}

void ViewServer::publish_solids(const json& solids) {
  std::lock_guard lock(mutex_);
  solids_ = solids.dump(-1, ' ', false, json::error_handler_t::replace);
}

void ViewServer::publish_picture(const json& picture) {
  std::lock_guard lock(mutex_);
  push("picture", picture);
}

bool ViewServer::frame_wanted() const {
  if (viewers_.load() == 0) return false;
  std::lock_guard lock(mutex_);
  const double since = clock_seconds() - frame_sent_at_;
  return since >= frame_interval_ && (frame_taken_ >= frame_seq_ || since >= 1.0);
}

ViewServer::Commands ViewServer::take_commands() {
  std::lock_guard lock(mutex_);
  Commands taken = commands_;
  commands_.step = commands_.stop = false;
  commands_.field.clear();
  commands_.picture.reset();
  return taken;
}

void ViewServer::wait_for_command(double seconds) {
  std::unique_lock lock(mutex_);
  changed_.wait_for(lock, std::chrono::duration<double>(seconds));
}

}  // namespace pbf

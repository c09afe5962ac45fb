#include "scripting/log_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <spdlog/pattern_formatter.h>
#include <spdlog/sinks/base_sink.h>
#include <spdlog/spdlog.h>

namespace pbf::log_file {

namespace {
std::mutex mutex;  // spdlog may log from OpenMP threads
std::FILE* file = nullptr;
std::function<void(std::string_view, bool)> console_writer;

// "%*" in the log pattern: "warning: " before warnings and errors, nothing before info,
// so thermo lines stay clean columns.
class LevelPrefix : public spdlog::custom_flag_formatter {
 public:
  void format(const spdlog::details::log_msg& msg, const std::tm&, spdlog::memory_buf_t& dest) override {
    static const std::string warning = "warning: ", error = "error: ", debug = "debug: ";
    const std::string* prefix = nullptr;
    if (msg.level == spdlog::level::warn) prefix = &warning;
    else if (msg.level >= spdlog::level::err) prefix = &error;
    else if (msg.level <= spdlog::level::debug) prefix = &debug;
    if (prefix) dest.append(prefix->data(), prefix->data() + prefix->size());
  }
  std::unique_ptr<custom_flag_formatter> clone() const override { return std::make_unique<LevelPrefix>(); }
};

// The log file's copy of every line the logger prints on the console, formatted the same way.
class LogFileSink : public spdlog::sinks::base_sink<std::mutex> {
 protected:
  void sink_it_(const spdlog::details::log_msg& msg) override {
    spdlog::memory_buf_t line;
    formatter_->format(msg, line);
    write({line.data(), line.size()});
  }
  void flush_() override {}  // write flushes every line
};

// Info lines on stdout, warnings and errors on stderr (where a user who sends the output to a
// file still sees them).
class ConsoleSink : public spdlog::sinks::base_sink<std::mutex> {
 protected:
  void sink_it_(const spdlog::details::log_msg& msg) override {
    spdlog::memory_buf_t line;
    formatter_->format(msg, line);
    console({line.data(), line.size()}, msg.level >= spdlog::level::warn);
  }
  void flush_() override { std::fflush(stdout); }
};

}  // namespace

std::string open(const std::string& path) {
  std::lock_guard<std::mutex> lock(mutex);
  if (file) std::fclose(file);
  file = std::fopen(path.c_str(), "we");  // 'e': close-on-exec, so ffmpeg (dump/movie) does not inherit it
  return file ? "" : std::strerror(errno);
}

void write(std::string_view text) {
  std::lock_guard<std::mutex> lock(mutex);
  if (!file) return;
  std::fwrite(text.data(), 1, text.size(), file);
  std::fflush(file);
}

bool close() {
  std::lock_guard<std::mutex> lock(mutex);
  if (!file) return true;
  const bool ok = !std::ferror(file);
  const bool closed = std::fclose(file) == 0;
  file = nullptr;
  return ok && closed;
}

void setup_logging(const std::string& level) {
  std::vector<spdlog::sink_ptr> sinks = {std::make_shared<ConsoleSink>(), std::make_shared<LogFileSink>()};
  auto logger = std::make_shared<spdlog::logger>("pbfengine", sinks.begin(), sinks.end());
  auto formatter = std::make_unique<spdlog::pattern_formatter>();
  formatter->add_flag<LevelPrefix>('*').set_pattern("%*%v");
  logger->set_formatter(std::move(formatter));
  logger->set_level(spdlog::level::from_str(level));
  logger->flush_on(spdlog::level::info);
  spdlog::set_default_logger(logger);
}

void console(std::string_view text, bool error) {
  if (console_writer) {
    console_writer(text, error);
    return;
  }
  std::FILE* stream = error ? stderr : stdout;
  if (error) std::fflush(stdout);  // what came before it comes first
  std::fwrite(text.data(), 1, text.size(), stream);
  std::fflush(stream);
}

void set_console(std::function<void(std::string_view, bool)> writer) { console_writer = std::move(writer); }

}  // namespace pbf::log_file

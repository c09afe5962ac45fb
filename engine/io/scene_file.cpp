#include "engine/io/scene_file.hpp"

#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <spdlog/spdlog.h>
#include <sstream>
#include <string_view>
#include <utility>

#include "engine/core/error.hpp"
#include "engine/core/real.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/io/text_lines.hpp"
#include "engine/sph/mass.hpp"
#include "engine/io/load_particles.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

namespace {

constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";

// The file's lines as tokens, and its numbers checked, each error naming the file and line.
class Reader {
 public:
  explicit Reader(const std::string& path) : lines_(path, "scene file") {}

  [[noreturn]] void fail(long line, const std::string& message) const { lines_.fail(line, message); }

  // The next non-comment line split into tokens; false at end of file (or of the share).
  bool next_line(std::vector<std::string>& tokens) {
    std::string text;
    while (lines_.next(text)) {
      // A UTF-8 byte-order mark, as some Windows editors write, is not part of the data.
      if (lines_.line() == 1 && text.starts_with(kByteOrderMark)) text.erase(0, kByteOrderMark.size());
      if (!is_data_line(text)) continue;
      tokens.clear();
      std::istringstream words(text);
      for (std::string w; words >> w;) tokens.push_back(w);
      return true;
    }
    return false;
  }

  double number(const std::string& token, const std::string& what) const {
    // from_chars refuses a leading '+'; skip one, but only before a digit or a point ("+-1").
    const bool plus = token.size() > 1 && token[0] == '+' && token[1] != '-';
    double value = 0;
    auto [end, ec] = std::from_chars(token.data() + plus, token.data() + token.size(), value);
    if (ec == std::errc::result_out_of_range)
      fail(line(), fmt::format("{}: '{}' is out of the range of a double", what, token));
    if (ec != std::errc() || end != token.data() + token.size())
      fail(line(), fmt::format("{}: '{}' is not a number", what, token));
    if (!std::isfinite(value)) fail(line(), fmt::format("{}: '{}' is not a finite number", what, token));
    return value;
  }

  // A number that becomes particle data (a position, a velocity, h, L), which may be single
  // precision (-DPBF_REAL=float): there a value beyond its range would become infinite, and
  // a positive one below it zero.
  double particle_number(const std::string& token, const std::string& what, bool positive = false) const {
    const double value = number(token, what);
    if (std::fabs(value) > static_cast<double>(std::numeric_limits<real>::max()))
      fail(line(), fmt::format("{}: '{}' is too large for the particle data's precision", what, token));
    if (positive && value > 0 && !(static_cast<real>(value) > 0))
      fail(line(), fmt::format("{}: '{}' is too small for the particle data's precision", what, token));
    return value;
  }

  long line() const { return lines_.line(); }
  TextLines& lines() { return lines_; }

 private:
  TextLines lines_;
};

}  // namespace

SceneFile read_scene_file(const std::string& path) {
  Reader reader(path);
  SceneFile scene;
  scene.path = path;
  static const char* header_names[6] = {"particle count N", "time step", "particle size h",
                                        "domain side L",    "output interval", "final time"};
  std::vector<std::string> tokens;
  long count_line = 0;
  int got = 0;
  double header[6] = {0, 0, 0, 0, 0, 0};
  while (got < 6) {
    if (!reader.next_line(tokens))
      reader.fail(reader.line(), fmt::format("the header ends early: missing the {} (six values: N, time step, h, "
                                             "L, output interval, final time)",
                                             header_names[got]));
    for (std::size_t t = 0; t < tokens.size(); ++t) {
      if (got == 6) reader.fail(reader.line(), fmt::format("unexpected '{}' after the six header values", tokens[t]));
      if (got == 0) {
        std::int64_t n = 0;
        auto [end, ec] = std::from_chars(tokens[t].data(), tokens[t].data() + tokens[t].size(), n);
        if (ec == std::errc::result_out_of_range)
          reader.fail(reader.line(), fmt::format("particle count N: '{}' is too large", tokens[t]));
        if (ec != std::errc() || end != tokens[t].data() + tokens[t].size())
          reader.fail(reader.line(), fmt::format("particle count N: '{}' is not an integer", tokens[t]));
        if (n <= 0) reader.fail(reader.line(), fmt::format("particle count N must be positive, got {}", n));
        scene.count = n;
        count_line = reader.line();
      } else {
        const bool length = got == 2 || got == 3;  // h and L; the times stay doubles
        header[got] = length ? reader.particle_number(tokens[t], header_names[got], true)
                             : reader.number(tokens[t], header_names[got]);
        if (!(header[got] > 0))
          reader.fail(reader.line(), fmt::format("{} must be positive, got {}", header_names[got], header[got]));
      }
      ++got;
    }
  }
  scene.dt = header[1];
  scene.h = header[2];
  scene.L = header[3];
  scene.interval = header[4];
  scene.t_final = header[5];

  // Particles (this process's share of the lines): never trust N for allocation before the
  // data confirm it.
  reader.lines().share_rest();
  const std::int64_t first = reader.lines().first_row();
  std::int64_t read = 0;
  while (reader.next_line(tokens)) {
    if (first + read == scene.count)
      reader.fail(reader.line(), fmt::format("more particle lines than the count N = {} given on line {}",
                                             scene.count, count_line));
    if (tokens.size() != 6)
      reader.fail(reader.line(), fmt::format("expected 6 values (x y z vx vy vz), found {}", tokens.size()));
    double p[6];
    static const char* names[6] = {"x", "y", "z", "vx", "vy", "vz"};
    for (int k = 0; k < 6; ++k) p[k] = reader.particle_number(tokens[k], names[k]);
    for (int k = 0; k < 3; ++k)
      if (p[k] < 0 || p[k] > scene.L)
        reader.fail(reader.line(), fmt::format("particle {} at ({}, {}, {}) is outside the domain [0, {}]^3",
                                               first + read, p[0], p[1], p[2], scene.L));
    scene.particles.insert(scene.particles.end(), p, p + 6);
    ++read;
  }
  const std::int64_t total = comm::sum(read);
  if (total != scene.count) {
    const long last = static_cast<long>(comm::max(static_cast<double>(reader.line())));  // the file's last line
    reader.fail(last, fmt::format("found {} particle line(s), but the count N on line {} is {}", total, count_line,
                                  scene.count));
  }
  scene.first_row = static_cast<std::size_t>(first);
  return scene;
}

double load_scene(Simulation& sim, const SceneFile& scene) {
  Domain domain;
  for (int a = 0; a < 3; ++a) {
    domain.lo[a] = 0;
    domain.hi[a] = scene.L;
  }
  sim.set_domain(domain);
  sim.set_kernel_radius(scene.h);
  sim.set_timestep(scene.dt);
  ParticleInput in;
  std::vector<double>* column[6] = {&in.x, &in.y, &in.z, &in.vx, &in.vy, &in.vz};
  const std::size_t n = scene.particles.size() / 6;
  for (int c = 0; c < 6; ++c) {
    column[c]->resize(n);
    for (std::size_t i = 0; i < n; ++i) (*column[c])[i] = scene.particles[6 * i + static_cast<std::size_t>(c)];
  }
  in.first_row = scene.first_row;
  in.total = static_cast<std::size_t>(scene.count);
  return add_particles(sim, std::move(in), scene.path).mass;
}

}  // namespace pbf

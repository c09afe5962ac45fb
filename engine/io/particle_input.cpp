#include "engine/io/particle_input.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <limits>

#include "engine/core/error.hpp"
#include "engine/core/real.hpp"
#include "engine/io/csv.hpp"
#include "engine/io/vtu.hpp"

namespace pbf {

ParticleTable read_particle_file(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  // Each process reads its share of the rows (a .vtu's XML head and each appended array whole,
  // one at a time; a .csv's lines of its block).
  if (ext == ".vtu") return read_vtu(path);
  if (ext == ".csv") return read_csv(path);
  throw Error(fmt::format("{}: unsupported particle file type '{}'; supported: .vtu (VTK UnstructuredGrid), "
                          ".csv (a header line, then one row per particle)",
                          path, ext.empty() ? "(no extension)" : ext),
              true);
}

namespace {

// Finds a vector quantity as one 3-component column or three scalar columns, and marks
// the columns it took in `used`. Returns false if the file has neither.
class Picker {
 public:
  explicit Picker(const ParticleTable& t) : table_(t), used_(t.columns.size(), false) {
    for (const auto& c : t.columns)
      if (c.values.size() != t.count * c.components)
        fail(fmt::format("column '{}' holds {} values, expected {} ({} particles x {} components)", c.name,
                         c.values.size(), t.count * c.components, t.count, c.components));
  }

  [[noreturn]] void fail(const std::string& message) const {
    throw Error(fmt::format("{}: {}", table_.path, message), true);
  }

  const Column* take(const std::string& name, int components) {
    const Column* c = table_.find(name);
    if (!c) return nullptr;
    if (c->components != components)
      fail(fmt::format("column '{}' has {} components, expected {}", name, c->components, components));
    used_[c - table_.columns.data()] = true;
    return c;
  }

  bool vector(const std::string& name, const char* const scalars[3], std::vector<double>* out[3]) {
    const std::size_t n = table_.count;
    if (const Column* v = take(name, 3)) {
      for (int d = 0; d < 3; ++d) {
        out[d]->resize(n);
        for (std::size_t i = 0; i < n; ++i) (*out[d])[i] = v->values[3 * i + d];
      }
      return true;
    }
    const Column* s[3];
    int found = 0;
    for (int d = 0; d < 3; ++d) found += (s[d] = table_.find(scalars[d])) != nullptr;
    if (found == 0) return false;
    if (found < 3)  // half a vector is a typo or a wrong file, not "absent"
      fail(fmt::format("columns {}, {}, {} go together, but {} is missing", scalars[0], scalars[1], scalars[2],
                       scalars[s[0] ? (s[1] ? 2 : 1) : 0]));
    for (int d = 0; d < 3; ++d) *out[d] = take(scalars[d], 1)->values;
    return true;
  }

  std::vector<std::string> unused() const {
    std::vector<std::string> names;
    for (std::size_t k = 0; k < used_.size(); ++k)
      if (!used_[k]) names.push_back(table_.columns[k].name);
    return names;
  }

  // The columns for a message: the first few, so a file of a million columns gives a
  // message of a line.
  std::string found() const {
    constexpr std::size_t kListed = 20;
    std::vector<std::string> names;
    for (const auto& c : table_.columns) {
      if (names.size() == kListed) break;
      names.push_back(c.components == 1 ? c.name : fmt::format("{} ({} components)", c.name, c.components));
    }
    if (table_.columns.size() > kListed) names.push_back(fmt::format("and {} more", table_.columns.size() - kListed));
    return names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", "));
  }

 private:
  const ParticleTable& table_;
  std::vector<bool> used_;
};

}  // namespace

ParticleInput interpret_particles(const ParticleTable& table) {
  Picker pick(table);
  ParticleInput in;
  static const char* const xyz[3] = {"x", "y", "z"};
  static const char* const vxyz[3] = {"vx", "vy", "vz"};
  // ParaView's "Save Data" as CSV names vector components NAME:0, NAME:1, NAME:2.
  static const char* const paraview_points[3] = {"Points:0", "Points:1", "Points:2"};
  static const char* const paraview_velocity[3] = {"velocity:0", "velocity:1", "velocity:2"};
  std::vector<double>* position[3] = {&in.x, &in.y, &in.z};
  std::vector<double>* velocity[3] = {&in.vx, &in.vy, &in.vz};
  if (!pick.vector("position", xyz, position) && !pick.vector("", paraview_points, position))
    pick.fail(fmt::format("no particle positions: expected a 3-component column 'position' or columns x, y, z "
                          "(or ParaView's Points:0, Points:1, Points:2); found: {}", pick.found()));
  if (table.total == 0) pick.fail("the file holds no particles");
  if (!pick.vector("velocity", vxyz, velocity) && !pick.vector("", paraview_velocity, velocity))
    for (auto* v : velocity) v->assign(table.count, 0.0);
  if (const Column* m = pick.take("mass", 1)) {
    in.has_mass = true;
    in.mass = m->values;
  }
  in.first_row = table.first_row;
  in.total = table.total;
  in.ignored = pick.unused();

  // Finite in the particle data's precision too: with -DPBF_REAL=float, a velocity of 1e39
  // would become infinite and a mass of 1e-50 zero.
  auto fits = [](double v) { return std::isfinite(v) && std::fabs(v) <= std::numeric_limits<real>::max(); };
  const char* precision = sizeof(real) == sizeof(double) ? "" : " in single precision";
  auto row = [&](std::size_t i) { return table.first_row + i; };  // in the file
  for (std::size_t i = 0; i < table.count; ++i) {
    if (!fits(in.x[i]) || !fits(in.y[i]) || !fits(in.z[i]))
      pick.fail(fmt::format("particle {} (0-based, in file order) has position ({}, {}, {}), not finite{}", row(i), in.x[i],
                            in.y[i], in.z[i], precision));
    if (!fits(in.vx[i]) || !fits(in.vy[i]) || !fits(in.vz[i]))
      pick.fail(fmt::format("particle {} (0-based, in file order) has velocity ({}, {}, {}), not finite{}", row(i),
                            in.vx[i], in.vy[i], in.vz[i], precision));
    if (in.has_mass && !(fits(in.mass[i]) && static_cast<real>(in.mass[i]) > 0))
      pick.fail(fmt::format("particle {} (0-based, in file order) has mass {}; masses must be positive and finite{}",
                            row(i), in.mass[i], precision));
  }
  return in;
}

}  // namespace pbf

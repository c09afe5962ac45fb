// Computes of the particles' motion and extent:
//   kinetic_energy  sum 1/2 m |v|^2 (J)
//   speed           max and mean of |v| (m/s)
//   count           number of particles
//   extent          min and max of x, y, z (m)
//   front           a percentile of one coordinate (m): a dam-break front that one
//                   stray droplet does not move
#include <algorithm>
#include <cmath>

#include "engine/error.hpp"
#include "engine/fixes/styles.hpp"
#include "engine/parallel.hpp"
#include "engine/simulation.hpp"

namespace pbf {

namespace {

class KineticEnergy : public Compute {
 public:
  KineticEnergy(const std::string& id, const Params&) : Compute(id, "kinetic_energy") {}
  std::vector<std::string> names() const override { return {"value"}; }
  void evaluate(Simulation& sim, std::vector<double>& values) override {
    const auto& P = sim.particles();
    values = {deterministic_sum(P.size(), [&](std::size_t i) {
      const double vx = P.vx()[i], vy = P.vy()[i], vz = P.vz()[i];
      return 0.5 * P.mass()[i] * (vx * vx + vy * vy + vz * vz);
    })};
  }
};

class Speed : public Compute {
 public:
  Speed(const std::string& id, const Params&) : Compute(id, "speed") {}
  std::vector<std::string> names() const override { return {"max", "avg"}; }
  void evaluate(Simulation& sim, std::vector<double>& values) override {
    const auto& P = sim.particles();
    auto speed = [&](std::size_t i) {
      const double vx = P.vx()[i], vy = P.vy()[i], vz = P.vz()[i];
      return std::sqrt(vx * vx + vy * vy + vz * vz);
    };
    double most = 0;
#pragma omp parallel for reduction(max : most)
    for (std::size_t i = 0; i < P.size(); ++i) most = std::max(most, speed(i));
    values = {most, deterministic_sum(P.size(), speed) / double(P.size())};
  }
};

class Count : public Compute {
 public:
  Count(const std::string& id, const Params&) : Compute(id, "count") {}
  std::vector<std::string> names() const override { return {"value"}; }
  void evaluate(Simulation& sim, std::vector<double>& values) override {
    values = {static_cast<double>(sim.particles().size())};
  }
};

class Extent : public Compute {
 public:
  Extent(const std::string& id, const Params&) : Compute(id, "extent") {}
  std::vector<std::string> names() const override { return {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"}; }
  void evaluate(Simulation& sim, std::vector<double>& values) override {
    const auto& P = sim.particles();
    const real* c[3] = {P.x(), P.y(), P.z()};
    values.clear();
    for (int a = 0; a < 3; ++a) {
      double lo = INFINITY, hi = -INFINITY;
      const real* ca = c[a];
#pragma omp parallel for reduction(min : lo) reduction(max : hi)
      for (std::size_t i = 0; i < P.size(); ++i) {
        lo = std::min(lo, double(ca[i]));
        hi = std::max(hi, double(ca[i]));
      }
      values.push_back(lo);
      values.push_back(hi);
    }
  }
};

class Front : public Compute {
 public:
  Front(const std::string& id, const Params& p) : Compute(id, "front"), percentile_(p.real("percentile")) {
    const std::string& axis = p.string("axis");
    if (axis != "x" && axis != "y" && axis != "z") throw Error("parameter 'axis' must be \"x\", \"y\" or \"z\"");
    axis_ = axis[0] - 'x';
    if (percentile_ < 0 || percentile_ > 100) throw Error("parameter 'percentile' must be in [0, 100]");
  }
  std::vector<std::string> names() const override { return {"value"}; }
  void evaluate(Simulation& sim, std::vector<double>& values) override {
    const auto& P = sim.particles();
    const real* c = axis_ == 0 ? P.x() : (axis_ == 1 ? P.y() : P.z());
    std::vector<real> coords(c, c + P.size());
    const auto k = static_cast<std::ptrdiff_t>(std::floor(percentile_ / 100 * double(coords.size() - 1) + 0.5));
    std::nth_element(coords.begin(), coords.begin() + k, coords.end());
    values = {double(coords[static_cast<std::size_t>(k)])};
  }

 private:
  double percentile_;
  int axis_ = 0;
};

template <class T>
auto maker() {
  return [](const std::string& id, const Params& p) { return std::make_unique<T>(id, p); };
}

}  // namespace

void register_compute_kinetic_energy(StyleRegistry& r) {
  r.add({"kinetic_energy", StyleKind::compute, "total kinetic energy, sum 1/2 m |v|^2 (J)", {}, nullptr,
         maker<KineticEnergy>()});
}

void register_compute_speed(StyleRegistry& r) {
  r.add({"speed", StyleKind::compute, "particle speed |v|: max and avg (m/s)", {}, nullptr, maker<Speed>()});
}

void register_compute_count(StyleRegistry& r) {
  r.add({"count", StyleKind::compute, "number of particles", {}, nullptr, maker<Count>()});
}

void register_compute_extent(StyleRegistry& r) {
  r.add({"extent", StyleKind::compute, "bounding box of the fluid: xmin, xmax, ymin, ymax, zmin, zmax (m)", {},
         nullptr, maker<Extent>()});
}

void register_compute_front(StyleRegistry& r) {
  r.add({"front",
         StyleKind::compute,
         "a high percentile of one coordinate (m), e.g. a dam-break surge front",
         {{"axis", ParamType::String, std::string("x"), "", "coordinate: \"x\", \"y\" or \"z\""},
          {"percentile", ParamType::Real, 99.0, "%", "percentile of the particles' coordinate"}},
         nullptr, maker<Front>()});
}

}  // namespace pbf

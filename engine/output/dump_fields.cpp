#include "engine/output/dump_fields.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/core/names.hpp"
#include "engine/core/simulation.hpp"
#include "engine/sph/velocity_curl.hpp"

namespace pbf {

namespace {

struct Derived {
  const char* name;
  const char* unit;
};
constexpr Derived kDerived[] = {{"id", ""},
                                {"density", "kg/m^3"},
                                {"density_error", ""},
                                {"summed_density", "kg/m^3"},
                                {"speed", "m/s"},
                                {"vorticity_magnitude", "1/s"}};

const Derived* derived(const std::string& name) {
  for (const auto& d : kDerived)
    if (name == d.name) return &d;
  return nullptr;
}

}  // namespace

std::vector<std::string> DumpFields::valid_names(const Simulation& sim) {
  std::vector<std::string> names;
  const auto& P = sim.particles();
  for (FieldId f : P.fields()) names.push_back(P.spec(f).name);
  for (const auto& d : kDerived)
    if (!P.find(d.name)) names.emplace_back(d.name);  // a declared field of that name wins
  return names;
}

void DumpFields::resolve(const Simulation& sim) {
  const auto& P = sim.particles();
  components_.clear();
  for (const auto& name : names_) {
    if (auto f = P.find(name)) {  // a field a fix keeps (wcsph's density) before a derived one
      components_.push_back(P.spec(*f).components);
    } else if (derived(name)) {
      components_.push_back(1);
    } else {
      const auto valid = valid_names(sim);
      throw Error(fmt::format("unknown field '{}'{}; valid fields: {}", name, did_you_mean(name, valid),
                              fmt::join(valid, ", ")));
    }
  }
}

std::string DumpFields::unit(std::size_t k) const {
  if (const Derived* d = derived(names_[k])) return d->unit;
  if (names_[k] == "position") return "m";
  if (names_[k] == "velocity") return "m/s";
  if (names_[k] == "mass") return "kg";
  return "";
}

std::vector<const real*> DumpFields::columns(Simulation& sim, std::size_t k) {
  auto& P = sim.particles();
  const std::size_t n = P.size();
  const std::string& name = names_[k];
  const int nc = components_[k];
  std::vector<const real*> columns;
  scratch_.resize(names_.size());
  std::vector<real>& scratch = scratch_[k];
  if (const auto f = P.find(name)) {
    for (int c = 0; c < nc; ++c) columns.push_back(P.data(*f, c));
  } else if (name == "density") {  // no solver keeps a density field: the SPH sum
    columns = {sim.solver_density()};
  } else if (name == "summed_density") {
    sim.refresh_neighbors();
    columns = {sim.summed_density().data()};
  } else if (name == "density_error") {
    const real* rho = sim.solver_density();
    scratch.resize(n);
    const real inverse = real(1 / sim.rest_density());
    for (std::size_t i = 0; i < n; ++i) scratch[i] = rho[i] * inverse - 1;
    columns = {scratch.data()};
  } else if (name == "speed") {
    scratch.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      scratch[i] = std::sqrt(P.vx()[i] * P.vx()[i] + P.vy()[i] * P.vy()[i] + P.vz()[i] * P.vz()[i]);
    columns = {scratch.data()};
  } else if (name == "vorticity_magnitude") {
    sim.refresh_neighbors();
    const std::vector<real>& volume = sim.summed_volume();
    sim.update_ghosts({P.vx(), P.vy(), P.vz()});
    std::vector<real> w(3 * n);
    scratch.resize(n);
    velocity_curl(sim, volume, w.data(), w.data() + n, w.data() + 2 * n, scratch.data());
    columns = {scratch.data()};
  } else if (name == "id") {
    throw Error("internal: the id field is gathered with gather_ids");
  }
  return columns;
}

void DumpFields::gather(Simulation& sim, std::size_t k, std::vector<real>& out) {
  const auto& P = sim.particles();
  const std::size_t n = P.size();
  const int nc = components_[k];
  const std::vector<const real*> columns = this->columns(sim, k);  // in memory order
  const std::vector<std::uint32_t> index = P.order_by_id();
  out.resize(n * static_cast<std::size_t>(nc));
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < n; ++k)
    for (int c = 0; c < nc; ++c) out[k * static_cast<std::size_t>(nc) + static_cast<std::size_t>(c)] = columns[c][index[k]];
}

void DumpFields::gather_ids(const Simulation& sim, std::vector<std::int64_t>& out) const {
  const auto& P = sim.particles();
  const std::vector<std::uint32_t> index = P.order_by_id();
  out.resize(index.size());
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = P.ids()[index[k]];
}

}  // namespace pbf

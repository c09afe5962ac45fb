#include "engine/core/particles.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <unistd.h>

#include "engine/core/error.hpp"
#include "engine/core/parallel.hpp"
#include "engine/distributed/comm.hpp"

namespace pbf {

Particles::Particles() {
  declare({"position", 3, "position (m)"});
  declare({"velocity", 3, "velocity (m/s)"});
  declare({"mass", 1, "mass (kg)"});
}

void Particles::add(const real position[3], const real velocity[3], real mass) {
  if (ghosts_) throw Error("Particles::add with ghosts present");
  for (int c = 0; c < 3; ++c) fields_[kPosition].data[c].push_back(position[c]);
  for (int c = 0; c < 3; ++c) fields_[kVelocity].data[c].push_back(velocity[c]);
  fields_[kMass].data[0].push_back(mass);
  for (std::size_t f = kMass + 1; f < fields_.size(); ++f)
    for (auto& component : fields_[f].data) component.push_back(0);  // none for a freed field
  ids_.push_back(next_id_++);
  if (distributed_) ++replicated_;
}

std::size_t Particles::global_size() const {
  if (!distributed_) return size();
  const std::int64_t own = static_cast<std::int64_t>(size() - replicated_);
  return static_cast<std::size_t>(comm::sum(own)) + replicated_;
}

void Particles::resize_all(std::size_t n) {
  for (Field& field : fields_)
    if (field.live)
      for (auto& component : field.data) component.resize(n, real(0));
  ids_.resize(n);
}

void Particles::append(std::span<const std::int64_t> ids) {
  if (ghosts_) throw Error("Particles::append with ghosts present");
  const std::size_t first = ids_.size();
  resize_all(first + ids.size());
  std::copy(ids.begin(), ids.end(), ids_.begin() + static_cast<std::ptrdiff_t>(first));
}

std::size_t Particles::add_ghosts(std::span<const std::int64_t> ids) {
  const std::size_t first = ids_.size();
  resize_all(first + ids.size());
  std::copy(ids.begin(), ids.end(), ids_.begin() + static_cast<std::ptrdiff_t>(first));
  ghosts_ += ids.size();
  return first;
}

void Particles::drop_ghosts() {
  resize_all(size());
  ghosts_ = 0;
}

void Particles::erase(const std::vector<char>& drop) {
  if (ghosts_) throw Error("Particles::erase with ghosts present");
  const std::size_t n = size();
  std::size_t kept = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (drop[i]) continue;
    if (kept != i) {
      for (Field& field : fields_)
        for (auto& component : field.data)
          if (!component.empty()) component[kept] = component[i];
      ids_[kept] = ids_[i];
    }
    ++kept;
  }
  resize_all(kept);
}

std::size_t Particles::remove(const std::vector<char>& drop) {
  if (ghosts_ || distributed_) throw Error("Particles::remove: only before the particles are distributed");
  const std::size_t n = size();
  std::vector<std::uint32_t> kept;
  kept.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
    if (!drop[i]) kept.push_back(static_cast<std::uint32_t>(i));
  if (kept.size() == n) return 0;
  for (Field& field : fields_)
    for (auto& component : field.data) {
      if (component.empty()) continue;  // a freed field
      for (std::size_t k = 0; k < kept.size(); ++k) component[k] = component[kept[k]];
      component.resize(kept.size());
    }
  // New ids: the rank of each remaining particle's old id.
  std::vector<std::int64_t> old_ids(kept.size());
  for (std::size_t k = 0; k < kept.size(); ++k) old_ids[k] = ids_[kept[k]];
  std::vector<std::uint32_t> by_id(kept.size());
  for (std::size_t k = 0; k < by_id.size(); ++k) by_id[k] = static_cast<std::uint32_t>(k);
  std::sort(by_id.begin(), by_id.end(), [&](std::uint32_t a, std::uint32_t b) { return old_ids[a] < old_ids[b]; });
  ids_.assign(kept.size(), 0);
  for (std::size_t rank = 0; rank < by_id.size(); ++rank) ids_[by_id[rank]] = static_cast<std::int64_t>(rank);
  next_id_ = static_cast<std::int64_t>(kept.size());
  return n - kept.size();
}

void Particles::fill(Field& field) const {
  field.data.assign(static_cast<std::size_t>(field.spec.components), std::vector<real>(ids_.size(), real(0)));
}

FieldId Particles::declare(const FieldSpec& spec) {
  for (FieldId f = 0; f < fields_.size(); ++f) {
    Field& field = fields_[f];
    if (field.spec.name != spec.name) continue;
    if (field.live && field.spec.components != spec.components)
      throw Error(fmt::format("field '{}' declared with {} and {} components", spec.name, field.spec.components,
                              spec.components));
    if (!field.live) {  // freed in an earlier round: back in its old slot
      field.spec = spec;
      fill(field);
      field.live = true;
    } else if (!field.declared) {  // the first declaration this round says what it is
      field.spec.doc = spec.doc;
      field.spec.restart = spec.restart;
    } else {  // several fixes share it: saved if any of them needs it
      field.spec.restart = field.spec.restart || spec.restart;
    }
    field.declared = true;
    return f;
  }
  Field field{spec, {}};
  fill(field);
  fields_.push_back(std::move(field));
  return fields_.size() - 1;
}

std::optional<FieldId> Particles::find(const std::string& name) const {
  for (FieldId f = 0; f < fields_.size(); ++f)
    if (fields_[f].live && fields_[f].spec.name == name) return f;
  return std::nullopt;
}

std::vector<FieldId> Particles::fields() const {
  std::vector<FieldId> live;
  for (FieldId f = 0; f < fields_.size(); ++f)
    if (fields_[f].live) live.push_back(f);
  return live;
}

void Particles::begin_declarations() {
  for (FieldId f = kMass + 1; f < fields_.size(); ++f) fields_[f].declared = false;
}

void Particles::free_undeclared() {
  for (FieldId f = kMass + 1; f < fields_.size(); ++f) {
    Field& field = fields_[f];
    if (field.declared || !field.live) continue;
    field.live = false;
    std::vector<std::vector<real>>().swap(field.data);
  }
}

double Particles::mean_mass() const {
  const real* m = mass();
  return deterministic_sum(size(), [&](std::size_t i) { return double(m[i]); }, distributed_) /
         static_cast<double>(global_size());
}

void Particles::reset(std::vector<std::int64_t> ids) {
  std::vector<char> seen(ids.size(), 0);
  for (std::int64_t id : ids) {
    if (id < 0 || static_cast<std::uint64_t>(id) >= ids.size() || seen[static_cast<std::size_t>(id)])
      throw Error(fmt::format("particle ids must be a permutation of 0..{}; found {}", ids.size() - 1, id));
    seen[static_cast<std::size_t>(id)] = 1;
  }
  ghosts_ = 0;
  ids_ = std::move(ids);
  next_id_ = static_cast<std::int64_t>(ids_.size());
  for (auto& field : fields_)
    if (field.live) fill(field);
}

void Particles::permute(std::span<const std::uint32_t> order, real* scratch) {
  if (ghosts_) throw Error("Particles::permute with ghosts present");
  const std::size_t n = order.size();
  std::vector<real> own;
  if (!scratch) {
    own.resize(n);
    scratch = own.data();
  }
  for (auto& field : fields_) {
    for (auto& component : field.data) {
      real* values = component.data();
#pragma omp parallel for schedule(static)
      for (std::size_t i = 0; i < n; ++i) scratch[i] = values[order[i]];
#pragma omp parallel for simd schedule(static)
      for (std::size_t i = 0; i < n; ++i) values[i] = scratch[i];
    }
  }
  id_scratch_.resize(n);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) id_scratch_[i] = ids_[order[i]];
  ids_.swap(id_scratch_);
}

std::vector<std::uint32_t> Particles::index_of_id() const {
  if (distributed_) throw Error("Particles::index_of_id: the particles are distributed among ranks");
  std::vector<std::uint32_t> index(size());
  for (std::size_t i = 0; i < size(); ++i) index[static_cast<std::size_t>(ids_[i])] = static_cast<std::uint32_t>(i);
  return index;
}

void check_memory_for(const Particles& particles, double count, const std::string& what) {
  const double bytes_per_particle = sizeof(real) == 4 ? 300.0 : 400.0;
  const double needed = (static_cast<double>(particles.size()) + count) * bytes_per_particle;
  const double machine = static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGESIZE));
  if (machine > 0 && !(needed <= machine))
    throw Error(fmt::format("{}: {:.4g} particles would need about {:.3g} GB of memory; this machine has {:.3g} GB",
                            what, static_cast<double>(particles.size()) + count, needed / 1e9, machine / 1e9));
}

}  // namespace pbf

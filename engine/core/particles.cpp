#include "engine/core/particles.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <unistd.h>

#include "engine/core/error.hpp"
#include "engine/core/parallel.hpp"
#include "engine/distributed/comm.hpp"

namespace pbf {

Particles::Particles() : distributed_(comm::distributed()) {
  declare({"position", 3, "position (m)"});
  declare({"velocity", 3, "velocity (m/s)"});
  declare({"mass", 1, "mass (kg)"});
}

void Particles::check_not_frozen(const char* what) const {
  if (frozen_)
    throw Error(fmt::format("particles {} during a step: only a fix's exchange hook (the step's start) may add or "
                            "remove particles",
                            what));
}

void Particles::add(const real position[3], const real velocity[3], real mass) {
  check_not_frozen("added");
  if (ghosts_) drop_ghosts();  // (the last run's: rebuilt when next needed)
  for (int c = 0; c < 3; ++c) fields_[kPosition].data[c].push_back(position[c]);
  for (int c = 0; c < 3; ++c) fields_[kVelocity].data[c].push_back(velocity[c]);
  fields_[kMass].data[0].push_back(mass);
  for (std::size_t f = kMass + 1; f < fields_.size(); ++f)
    for (auto& component : fields_[f].data) component.push_back(0);  // none for a freed field
  ids_.push_back(next_id_++);
}

Particles::Share Particles::share_of(std::size_t count, bool distributed) {
  if (!distributed) return {0, count};
  const auto rank = static_cast<unsigned __int128>(comm::rank()), ranks = static_cast<unsigned __int128>(comm::ranks());
  return {static_cast<std::size_t>(count * rank / ranks), static_cast<std::size_t>(count * (rank + 1) / ranks)};
}

std::size_t Particles::finish_source(std::size_t first) {
  const std::size_t added = size() - first;
  if (!distributed_) return added;
  // add() numbered them on from next_id_ as if this rank were alone.
  const std::int64_t base = next_id_ - static_cast<std::int64_t>(added);
  const std::int64_t before = comm::exclusive_sum(static_cast<std::int64_t>(added));
  const auto total = static_cast<std::size_t>(comm::sum(static_cast<std::int64_t>(added)));
  for (std::size_t k = 0; k < added; ++k) ids_[first + k] = base + before + static_cast<std::int64_t>(k);
  next_id_ = base + static_cast<std::int64_t>(total);
  global_ += total;
  unplaced_ += total;
  return total;
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
  check_not_frozen("removed");
  const std::size_t n = size();
  std::size_t removed = 0;
  for (std::size_t i = 0; i < n; ++i) removed += drop[i] ? 1 : 0;
  // (Whether any rank removes one: the common case, none, costs one sum.)
  const auto all = static_cast<std::size_t>(distributed_ ? comm::sum(static_cast<std::int64_t>(removed))
                                                         : static_cast<std::int64_t>(removed));
  if (all == 0) return 0;
  if (ghosts_) drop_ghosts();  // (rebuilt when next needed)
  erase(drop);
  global_ -= all;
  unplaced_ = std::min(unplaced_, global_);
  return removed;
}

void Particles::fill(Field& field) const {
  field.data.assign(static_cast<std::size_t>(field.spec.components), RealArray(ids_.size(), real(0)));
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
    std::vector<RealArray>().swap(field.data);
  }
}

double Particles::mean_mass() const {
  const real* m = mass();
  return deterministic_sum(size(), [&](std::size_t i) { return double(m[i]); }, distributed_) /
         static_cast<double>(global_size());
}

void Particles::reset(std::vector<std::int64_t> ids, std::int64_t next_id) {
  check_ids(ids, next_id);
  ghosts_ = 0;
  ids_.assign(ids.begin(), ids.end());
  next_id_ = settled_ = next_id;  // their fields are the file's
  global_ = ids_.size();
  unplaced_ = distributed_ ? global_ : 0;
  for (auto& field : fields_)
    if (field.live) fill(field);
}

void Particles::reset_share(std::vector<std::int64_t> ids, std::size_t global, std::int64_t next_id) {
  check_ids(ids, next_id);
  ghosts_ = 0;
  ids_.assign(ids.begin(), ids.end());
  next_id_ = settled_ = next_id;
  global_ = global;
  unplaced_ = global;
  for (auto& field : fields_)
    if (field.live) fill(field);
}

void check_ids(std::span<const std::int64_t> ids, std::int64_t next_id) {
  std::vector<std::int64_t> sorted(ids.begin(), ids.end());
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t k = 0; k < sorted.size(); ++k) {
    if (sorted[k] < 0 || sorted[k] >= next_id)
      throw Error(fmt::format("particle id {} outside 0..{} (the next id to give is {})", sorted[k], next_id - 1,
                              next_id));
    if (k > 0 && sorted[k] == sorted[k - 1]) throw Error(fmt::format("particle id {} is held twice", sorted[k]));
  }
}

void Particles::swap_values(FieldId field, int component, RealArray& values) {
  auto& mine = fields_[field].data[static_cast<std::size_t>(component)];
  if (values.size() != mine.size())
    throw Error(fmt::format("Particles::swap_values: field '{}' has {} values, the array to swap {}",
                            fields_[field].spec.name, mine.size(), values.size()));
  mine.swap(values);
}

void Particles::permute(std::span<const std::uint32_t> order, RealArray* buffer) {
  if (ghosts_) throw Error("Particles::permute with ghosts present");
  const std::size_t n = order.size();
  RealArray own;
  RealArray& next = buffer ? *buffer : own;
  next.resize(n);
  // Each array gathered into `next`, which then takes its place: one pass per array.
  for (auto& field : fields_) {
    for (auto& component : field.data) {
      const real* values = component.data();
      real* into = next.data();
      for_particles(n, [&](std::size_t i) { into[i] = values[order[i]]; });
      component.swap(next);
    }
  }
  id_scratch_.resize(n);
  for_particles(n, [&](std::size_t i) { id_scratch_[i] = ids_[order[i]]; });
  ids_.swap(id_scratch_);
}

std::vector<std::uint32_t> Particles::order_by_id() const {
  const std::size_t n = size();
  std::vector<std::uint32_t> order(n);
  if (n == 0) return order;
  const auto [lo, hi] = std::minmax_element(ids_.begin(), ids_.begin() + static_cast<std::ptrdiff_t>(n));
  const auto range = static_cast<std::uint64_t>(*hi - *lo) + 1;
  if (range <= 2 * static_cast<std::uint64_t>(n)) {  // few gaps: a bucket per id, in one pass
    std::vector<std::uint32_t> slot(range, kNoIndex);
    for (std::size_t i = 0; i < n; ++i) slot[static_cast<std::size_t>(ids_[i] - *lo)] = static_cast<std::uint32_t>(i);
    std::size_t k = 0;
    for (std::uint32_t i : slot)
      if (i != kNoIndex) order[k++] = i;
    return order;
  }
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(i);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return ids_[a] < ids_[b]; });
  return order;
}

std::vector<std::uint32_t> Particles::index_of_id() const {
  if (distributed_) throw Error("Particles::index_of_id: the particles are distributed among ranks");
  std::vector<std::uint32_t> index(static_cast<std::size_t>(next_id_), kNoIndex);
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

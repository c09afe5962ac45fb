#include "engine/particles.hpp"

#include <algorithm>
#include <fmt/format.h>

#include "engine/error.hpp"

namespace pbf {

Particles::Particles() {
  declare({"position", 3, "position (m)"});
  declare({"velocity", 3, "velocity (m/s)"});
  declare({"mass", 1, "mass (kg)"});
}

void Particles::add(const real position[3], const real velocity[3], real mass) {
  for (int c = 0; c < 3; ++c) fields_[kPosition].data[c].push_back(position[c]);
  for (int c = 0; c < 3; ++c) fields_[kVelocity].data[c].push_back(velocity[c]);
  fields_[kMass].data[0].push_back(mass);
  for (std::size_t f = kMass + 1; f < fields_.size(); ++f)
    for (auto& component : fields_[f].data) component.push_back(0);
  ids_.push_back(static_cast<std::int64_t>(ids_.size()));
}

FieldId Particles::declare(const FieldSpec& spec) {
  if (auto existing = find(spec.name)) {
    if (fields_[*existing].spec.components != spec.components)
      throw Error(fmt::format("field '{}' declared with {} and {} components", spec.name,
                              fields_[*existing].spec.components, spec.components));
    return *existing;
  }
  Field field{spec, std::vector<std::vector<real>>(spec.components, std::vector<real>(size(), real(0)))};
  fields_.push_back(std::move(field));
  return fields_.size() - 1;
}

std::optional<FieldId> Particles::find(const std::string& name) const {
  for (FieldId f = 0; f < fields_.size(); ++f)
    if (fields_[f].spec.name == name) return f;
  return std::nullopt;
}

void Particles::retain_fields(const std::vector<std::string>& keep) {
  auto dropped = [&](const Field& field) {
    return std::find(keep.begin(), keep.end(), field.spec.name) == keep.end();
  };
  fields_.erase(std::remove_if(fields_.begin() + kMass + 1, fields_.end(), dropped), fields_.end());
}

void Particles::reset(std::vector<std::int64_t> ids) {
  std::vector<char> seen(ids.size(), 0);
  for (std::int64_t id : ids) {
    if (id < 0 || static_cast<std::uint64_t>(id) >= ids.size() || seen[static_cast<std::size_t>(id)])
      throw Error(fmt::format("particle ids must be a permutation of 0..{}; found {}", ids.size() - 1, id));
    seen[static_cast<std::size_t>(id)] = 1;
  }
  ids_ = std::move(ids);
  for (auto& field : fields_)
    for (auto& component : field.data) component.assign(ids_.size(), real(0));
}

void Particles::permute(const std::vector<std::uint32_t>& order) {
  std::vector<real> scratch(size());
  for (auto& field : fields_) {
    for (auto& component : field.data) {
#pragma omp parallel for schedule(static)
      for (std::size_t i = 0; i < order.size(); ++i) scratch[i] = component[order[i]];
      component.swap(scratch);
    }
  }
  std::vector<std::int64_t> ids(size());
  for (std::size_t i = 0; i < order.size(); ++i) ids[i] = ids_[order[i]];
  ids_.swap(ids);
}

std::vector<std::uint32_t> Particles::index_of_id() const {
  std::vector<std::uint32_t> index(size());
  for (std::size_t i = 0; i < size(); ++i) index[static_cast<std::size_t>(ids_[i])] = static_cast<std::uint32_t>(i);
  return index;
}

}  // namespace pbf

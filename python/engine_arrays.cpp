// The particle arrays as NumPy arrays over the engine's memory (python/engine.hpp).
//
// An array views one component of one field for this rank's own particles (not the ghosts),
// in memory order, as the engine's type (float32 or float64 as built). Its base holds a pin
// on the block it views (engine/core/field_array.hpp), so the block outlives any use of the
// array: a stale view can show old values, never freed memory. python/pbfengine/_views.py
// makes the stale ones refuse use.
#include <fmt/format.h>

#include <cstring>

#include "engine/core/error.hpp"
#include "engine/core/field_array.hpp"
#include "engine/core/names.hpp"
#include "engine/distributed/comm.hpp"
#include "python/engine.hpp"

namespace pbf::python {

namespace {

// An array over `count` values at `data`, pinned while the array lives.
template <class T>
py::array pinned_array(T* data, std::size_t count, bool writable) {
  if (count == 0) return py::array_t<T>(0);
  buffer_pins::pin(data);
  py::capsule pin(data, [](void* block) { buffer_pins::unpin(block); });
  py::array array(py::dtype::of<T>(), {static_cast<py::ssize_t>(count)}, {static_cast<py::ssize_t>(sizeof(T))}, data,
                  pin);
  if (!writable) py::detail::array_proxy(array.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return array;
}

}  // namespace

FieldId Engine::field_id(const std::string& name) const {
  if (auto id = sim_->particles().find(name)) return *id;
  std::vector<std::string> names;
  for (FieldId f : sim_->particles().fields()) names.push_back(sim_->particles().spec(f).name);
  throw Error(fmt::format("no particle field '{}'{}; the fields now are {} (a fix declares its fields when a run "
                          "starts)",
                          name, did_you_mean(name, names), fmt::join(names, ", ")));
}

py::list Engine::fields() const {
  py::list list;
  for (FieldId f : sim_->particles().fields()) {
    const FieldSpec& spec = sim_->particles().spec(f);
    list.append(py::make_tuple(spec.name, spec.components, spec.doc));
  }
  return list;
}

py::array Engine::view(const std::string& name, int component, bool writable) {
  const FieldId f = field_id(name);
  const int components = sim_->particles().spec(f).components;
  if (component < 0 || component >= components)
    throw Error(fmt::format("field '{}' has {} component{}: component {} does not exist", name, components,
                            components == 1 ? "" : "s", component));
  // A change to the positions invalidates what the engine derived from them (neighbour
  // lists, summed densities).
  if (writable && f == Particles::kPosition) sim_->positions_changed();
  return pinned_array(sim_->particles().data(f, component), sim_->particles().size(), writable);
}

py::array Engine::ids() {
  return pinned_array(const_cast<std::int64_t*>(sim_->particles().ids()), sim_->particles().size(), false);
}

std::uintptr_t Engine::address(const std::string& name, int component) {
  return reinterpret_cast<std::uintptr_t>(sim_->particles().data(field_id(name), component));
}

py::object Engine::gather(const std::string& name) {
  const FieldId f = field_id(name);
  const Particles& P = sim_->particles();
  const int components = P.spec(f).components;
  const std::size_t n = P.size();
  // Each rank's (id, values...) records; rank 0 orders every rank's by id.
  const std::size_t record = sizeof(std::int64_t) + components * sizeof(real);
  std::vector<char> bytes(n * record);
  for (std::size_t i = 0; i < n; ++i) {
    char* at = bytes.data() + i * record;
    std::memcpy(at, P.ids() + i, sizeof(std::int64_t));
    for (int c = 0; c < components; ++c)
      std::memcpy(at + sizeof(std::int64_t) + c * sizeof(real), P.data(f, c) + i, sizeof(real));
  }
  std::vector<std::vector<char>> all;
  if (comm::distributed()) all = comm::gather_bytes(bytes);
  else all.push_back(std::move(bytes));
  if (!comm::root()) return py::none();
  std::vector<const char*> records;
  for (const auto& part : all)
    for (std::size_t k = 0; k < part.size() / record; ++k) records.push_back(part.data() + k * record);
  auto id_of = [](const char* r) {
    std::int64_t id;
    std::memcpy(&id, r, sizeof id);
    return id;
  };
  std::sort(records.begin(), records.end(), [&](const char* a, const char* b) { return id_of(a) < id_of(b); });
  const auto count = static_cast<py::ssize_t>(records.size());
  py::array_t<std::int64_t> ids(count);
  py::array_t<real> values = components == 1 ? py::array_t<real>(count) : py::array_t<real>({count, py::ssize_t(components)});
  auto* id_out = ids.mutable_data();
  real* value_out = values.mutable_data();
  for (py::ssize_t k = 0; k < count; ++k) {
    id_out[k] = id_of(records[k]);
    std::memcpy(value_out + k * components, records[k] + sizeof(std::int64_t), components * sizeof(real));
  }
  py::dict d;
  d["id"] = ids;
  d[py::str(name)] = values;
  return d;
}

}  // namespace pbf::python

// A frame of the live view (engine/view/view_frame.hpp).
#include "engine/view/view_frame.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <span>

#include "engine/core/simulation.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/sph/mass.hpp"

namespace pbf {

void ViewFrame::choose(const Simulation& sim, const std::string& field) {
  field_.reset();
  if (field == "id") return;
  field_.emplace(Names{field});
  field_->resolve(sim);
}

double ViewFrame::spacing(const Simulation& sim) {
  const double mass = sim.particle_mass();
  return mass > 0 ? lattice_spacing(mass, sim.kernels(), sim.rest_density()) : sim.kernel_radius();
}

std::shared_ptr<const std::string> ViewFrame::gather(Simulation& sim, std::uint64_t seq, std::int64_t most_points) {
  // (A field that reads neighbours, density, refreshes them in columns(), before the
  // positions are read below: the speed and the id need none, and cost no neighbour search.)
  const auto& P = sim.particles();
  const std::size_t n = P.size();
  const std::vector<const real*> columns = field_ ? field_->columns(sim, 0) : std::vector<const real*>{};
  const auto total = static_cast<std::int64_t>(sim.global_count());
  stride_ = std::max<std::int64_t>(1, (total + most_points - 1) / most_points);
  mine_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    if (P.ids()[i] % stride_ != 0) continue;
    double value = 0;
    if (!field_) {
      value = static_cast<double>(P.ids()[i]);
    } else if (columns.size() == 1) {
      value = columns[0][i];
    } else {
      for (const real* c : columns) value += double(c[i]) * double(c[i]);
      value = std::sqrt(value);
    }
    mine_.insert(mine_.end(), {static_cast<float>(P.x()[i]), static_cast<float>(P.y()[i]),
                               static_cast<float>(P.z()[i]), static_cast<float>(value)});
  }
  std::vector<std::vector<char>> parts;
  const auto bytes = std::span<const char>(reinterpret_cast<const char*>(mine_.data()), mine_.size() * sizeof(float));
  if (P.distributed()) {
    parts = comm::gather_bytes(bytes);
    if (!comm::root()) return nullptr;
  } else {
    parts.emplace_back(bytes.begin(), bytes.end());
  }
  count_ = 0;
  for (const auto& part : parts) count_ += part.size() / (4 * sizeof(float));
  auto frame = std::make_shared<std::string>(kHeaderBytes + 16 * count_, '\0');
  char* out = frame->data();
  const std::uint32_t count32 = static_cast<std::uint32_t>(count_), seq32 = static_cast<std::uint32_t>(seq);
  const double time = sim.time();
  const std::int64_t step = sim.step();
  std::memcpy(out, "PBFV", 4);  // (the machines this runs on are little-endian, as the page reads)
  std::memcpy(out + 4, &count32, 4);
  std::memcpy(out + 8, &time, 8);
  std::memcpy(out + 16, &step, 8);
  std::memcpy(out + 24, &seq32, 4);
  float* xyz = reinterpret_cast<float*>(out + kHeaderBytes);
  float* values = xyz + 3 * count_;
  low_ = INFINITY, high_ = -INFINITY;
  std::size_t at = 0;
  for (const auto& part : parts) {
    const std::size_t m = part.size() / (4 * sizeof(float));
    const float* records = reinterpret_cast<const float*>(part.data());
    for (std::size_t i = 0; i < m; ++i, ++at) {
      std::copy(records + 4 * i, records + 4 * i + 3, xyz + 3 * at);
      values[at] = records[4 * i + 3];
      if (std::isfinite(values[at])) low_ = std::min(low_, double(values[at])), high_ = std::max(high_, double(values[at]));
    }
  }
  if (!(low_ <= high_)) low_ = high_ = 0;
  return frame;
}

}  // namespace pbf

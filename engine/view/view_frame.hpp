#pragma once
// One frame of the live view: every particle's position and the chosen colour field's value
// (a vector field's magnitude), gathered on rank 0 and packed in the layout the page reads
// (docs/design.md#the-live-view): a 32-byte header ("PBFV", count, time, step, sequence
// number), then float32 x, y, z of each particle, then float32 values.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/output/dump_fields.hpp"

namespace pbf {

class Simulation;

class ViewFrame {
 public:
  static constexpr std::size_t kHeaderBytes = 32;

  // The colour field from now on (a name DumpFields knows, or "id").
  void choose(const Simulation& sim, const std::string& field);
  // The particle spacing, which the page draws points at.
  static double spacing(const Simulation& sim);
  // Collective: the frame's bytes on rank 0 (nullptr on the others). Of more than
  // `most_points` particles, those whose id is a multiple of k, the least k that leaves at most
  // that many: the same particles frame after frame, so a thinned cloud does not flicker.
  std::shared_ptr<const std::string> gather(Simulation& sim, std::uint64_t seq, std::int64_t most_points);
  // Of the last frame: one particle in `stride()` by id.
  std::int64_t stride() const { return stride_; }
  // Of the last frame gathered (rank 0): particles, the values' range and unit.
  std::size_t count() const { return count_; }
  double low() const { return low_; }
  double high() const { return high_; }
  std::string unit() const { return field_ ? field_->unit(0) : "-"; }

 private:
  std::optional<DumpFields> field_;  // none: the id
  std::vector<float> mine_;          // this rank's x, y, z, value per particle
  std::size_t count_ = 0;
  std::int64_t stride_ = 1;
  double low_ = 0, high_ = 0;
};

}  // namespace pbf

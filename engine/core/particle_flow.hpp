#pragma once
// What a fix has let into the scene (an emitter) or out of it (outflow, a box's open faces)
// since the scene began: a count and the mass, summed exactly (the same bits at any thread and
// rank count, and across restarts, which keep the tally), so that a scene's mass balance,
// initial + in - out = present, holds to the rounding of its four terms. The `flow` compute
// reads it as thermo columns.
#include <cstdint>
#include <vector>

#include "engine/core/exact_sum.hpp"

namespace pbf {

class Particles;
class ByteWriter;
class ByteReader;

class ParticleFlow {
 public:
  // Counts this rank's particles with flag[i] set, on every rank (collective in a
  // distributed run): call it before removing them.
  void count_marked(const Particles& P, const std::vector<char>& flag);
  // Counts this rank's particles from index `first` on (those just added; collective).
  void count_from(const Particles& P, std::size_t first);
  std::int64_t count() const { return count_; }
  double mass() const { return mass_.value(); }
  void save(ByteWriter& w) const;
  void restore(ByteReader& r);

 private:
  void add(std::int64_t count, ExactSum& mass, bool distributed);
  std::int64_t count_ = 0;
  ExactSum mass_;
};

}  // namespace pbf

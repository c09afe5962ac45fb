#pragma once
// A compute measures the state: named scalar values (thermo columns, Lua numbers) or one
// value per particle (a Lua array in input order, later a dump column).
#include <string>
#include <vector>

namespace pbf {

class Simulation;

class Compute {
 public:
  Compute(std::string id, std::string style) : id_(std::move(id)), style_(std::move(style)) {}
  virtual ~Compute() = default;

  const std::string& id() const { return id_; }
  const std::string& style() const { return style_; }

  // Names of the scalar values; a single value is addressed by the compute's id alone,
  // several as "id.name". Empty for a per-particle compute.
  virtual std::vector<std::string> names() const = 0;
  virtual void evaluate(Simulation& sim, std::vector<double>& values) = 0;

  virtual bool per_particle() const { return false; }
  // Whether it measures over every rank's particles in a distributed run (else refused there).
  virtual bool runs_distributed() const { return false; }
  // One value per particle, indexed by particle id (the input order).
  virtual void evaluate_per_particle(Simulation&, std::vector<double>& by_id) { by_id.clear(); }

 private:
  std::string id_, style_;
};

}  // namespace pbf

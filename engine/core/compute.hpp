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

  // Names of the scalar values; empty for a per-particle compute.
  virtual std::vector<std::string> names() const = 0;
  // The unit of each value, in the order of names(): SI, "-" for a pure number (a count, a
  // ratio), "m/s", "N m", ...
  virtual std::vector<std::string> units() const = 0;
  // Whether a single value keeps its name in columns(): one a script named (a probe's label).
  virtual bool names_single_value() const { return false; }
  // The names thermo columns and CSV headers use: "id.name" for each value, or the id alone
  // for a single value whose name says nothing more (a count, an energy).
  std::vector<std::string> columns() const {
    const auto values = names();
    if (values.size() == 1 && !names_single_value()) return {id_};
    std::vector<std::string> out;
    for (const auto& name : values) out.push_back(id_ + "." + name);
    return out;
  }
  virtual void evaluate(Simulation& sim, std::vector<double>& values) = 0;

  // Checks the compute against the scene: when it is added (if the domain is set) and as a
  // run starts, after every fix's init (solids have their maps then). Throws what cannot be
  // measured, warns about what measures nothing (a probe's point outside the domain, inside
  // a solid).
  virtual void check_scene(const Simulation&) {}

  virtual bool per_particle() const { return false; }
  // Whether it measures over every rank's particles in a distributed run (else refused there).
  virtual bool runs_distributed() const { return false; }
  // One value per particle of every rank, in ascending id order, with the ids.
  virtual void evaluate_per_particle(Simulation&, std::vector<std::int64_t>& ids, std::vector<double>& values) {
    ids.clear();
    values.clear();
  }

 private:
  std::string id_, style_;
};

}  // namespace pbf

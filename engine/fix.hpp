#pragma once
// A fix is one style instance in the step pipeline (LAMMPS's word): it names the stages
// it joins and implements a hook for each. The run loop calls and times the hooks; a fix
// never times itself.
#include <string>
#include <vector>

#include "engine/stage.hpp"

namespace pbf {

class Simulation;
class DensityBoundary;

// Order within a stage: the solver first, boundaries last, other fixes between them in
// script order. So in each constraint iteration the density correction runs before the
// wall projection, and walls correct velocities after the solver has set them.
enum class Role { solver = 0, other = 1, boundary = 2 };

class Fix {
 public:
  Fix(std::string id, std::string style) : id_(std::move(id)), style_(std::move(style)) {}
  virtual ~Fix() = default;

  const std::string& id() const { return id_; }
  const std::string& style() const { return style_; }

  virtual std::vector<Stage> stages() const = 0;
  virtual Role role() const { return Role::other; }
  // How many constraint iterations a step needs (the run takes the largest; at least 1).
  virtual int constraint_iterations() const { return 0; }
  virtual bool needs_neighbors() const { return false; }
  // Walls that add to the density the solver sees (nullptr: none).
  virtual DensityBoundary* density_boundary() { return nullptr; }

  // Start of every run: declare fields, precompute constants, write initial output.
  virtual void init(Simulation&) {}
  virtual void external_forces(Simulation&) {}
  virtual void predict(Simulation&) {}
  virtual void forces(Simulation&) {}
  virtual void constraint(Simulation&, int /*iteration*/) {}
  virtual void velocity_update(Simulation&) {}
  virtual void velocity_post(Simulation&) {}
  virtual void end_of_step(Simulation&) {}
  // End of every run (flush files).
  virtual void finish(Simulation&) {}

  // Fields this fix declared in init(); fields no fix declares are freed.
  const std::vector<std::string>& fields() const { return fields_; }

 protected:
  std::vector<std::string> fields_;

 private:
  std::string id_, style_;
};

}  // namespace pbf

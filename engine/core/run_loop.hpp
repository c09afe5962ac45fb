#pragma once
// The run loop of Simulation::run, internal to the engine: run_loop.cpp runs the stages of
// each step, run_loop_checks.cpp checks what a run starts from and what each hook leaves, and
// makes the stops and restarts that signals ask for.
#include <array>
#include <cstdint>
#include <omp.h>
#include <string>
#include <vector>

#include "engine/core/run_view.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

constexpr Role kRoles[] = {Role::solver, Role::other, Role::boundary, Role::output};
// A run of more steps is refused (days of computing, or an end time or a time step in the
// wrong unit); one of more than kManySteps gets a warning.
constexpr double kMostSteps = 1e9, kManySteps = 1e7;

class RunLoop {
 public:
  explicit RunLoop(Simulation& sim) : sim_(sim) {}
  // `steps` steps, or (steps < 0) until the time reaches `until`.
  void run(std::int64_t steps, double until);

 private:
  struct Hook {
    Fix* fix;
    std::size_t row;  // timing row
  };
  void plan(std::int64_t steps, double until);
  void prepare();
  void check_start_state() const;
  // Every particle's mass positive and finite (a Python program may write them).
  void check_masses() const;
  void check_pipeline() const;
  void distribute();
  void init_new_particles();
  void step();
  void exchange();
  void run_stage(Stage stage, int iteration = 0);
  void call(Stage stage, Fix& fix, int iteration);
  void check_finite(Stage stage, const Fix& fix) const;
  void check_end_of_step(std::int64_t step) const;
  std::size_t first_non_finite() const;
  std::string blew_up(std::size_t i) const;
  void check_clumping() const;
  [[noreturn]] void stop_interrupted(const std::string& reason);
  // After a step: what signals and the live view ask for, agreed over the ranks; holds the run
  // while the view pauses it.
  void after_step();
  std::string write_restart_now(const char* prefix);
  double now() const { return omp_get_wtime(); }

  Simulation& sim_;
  TimingTable& timing_ = sim_.timing_;
  RunView* view_ = nullptr;  // the live view's fix, if the pipeline has one
  double held_seconds_ = 0;  // time the view held the run: not the run's speed
  std::array<std::vector<Hook>, kStageCount> hooks_;
  void iterate(Stage stage, Simulation::SolverReport::Loop& report);
  int most_iterations_[kStageCount] = {};  // of each repeated stage (at least 1)
  bool neighbors_ = false;
  std::size_t row_view_ = 0;  // the live view's work after each step (frames, pictures)
  std::size_t row_reorder_ = 0, row_binning_ = 0, row_lists_ = 0, row_checks_ = 0, row_thermo_ = 0, row_migrate_ = 0, row_ghosts_ = 0;
  double neighbor_mean_sum_ = 0;
  long long neighbor_builds_ = 0;
  double full_neighborhood_ = 0;  // particles within h of one at rest density
  std::vector<std::uint32_t> fresh_;  // the new particles' indices (init_new_particles)
};

}  // namespace pbf

// iterations: what a solver's repeated stage did (`loop`: the constraints, pbf's and dfsph's
// density solve; or the divergence, dfsph's divergence-free solve). last = iterations of
// the last step; avg = their mean over the steps since this compute was last evaluated (a
// thermo line: the average since the previous line); error = the error the solver measured
// in its last iteration, before that iteration's correction (0 before the first step): pbf's
// mean compression, mean of max(rho/rho0 - 1, 0); dfsph's mean predicted compression, or
// its mean density change over one step from the velocity's divergence, relative to rho0.
#include "engine/registry/builtin_styles.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

namespace {

class Iterations : public Compute {
 public:
  Iterations(const std::string& id, const Params& p)
      : Compute(id, "iterations"), divergence_(p.string("loop") == "divergence") {}
  std::vector<std::string> names() const override { return {"last", "avg", "error"}; }
  std::vector<std::string> units() const override { return {"-", "-", "-"}; }
  bool runs_distributed() const override { return true; }  // the solver's report is the same on every rank
  void evaluate(Simulation& sim, std::vector<double>& values) override {
    const auto& solver = sim.solver_report();
    const auto& report = divergence_ ? solver.divergence : solver.constraints;
    const std::int64_t steps = solver.steps - steps_seen_, sum = report.iteration_sum - sum_seen_;
    const double avg = steps > 0 ? double(sum) / double(steps) : double(report.iterations);
    steps_seen_ = solver.steps;
    sum_seen_ = report.iteration_sum;
    values = {double(report.iterations), avg, report.error};
  }

 private:
  bool divergence_;
  std::int64_t steps_seen_ = 0, sum_seen_ = 0;
};

}  // namespace

void register_compute_iterations(StyleRegistry& r) {
  r.add({"iterations", StyleKind::compute,
         "solver iterations: last (of the last step), avg (since the previous evaluation), error (what the solver "
         "measured in the last iteration, before its correction)",
         {ParamSpec{"loop", ParamType::String, std::string("constraints"), "",
                    "constraints: the density solve (pbf, dfsph); divergence: dfsph's divergence-free solve"}
              .one_of({"constraints", "divergence"})},
         nullptr, make_compute<Iterations>(),
         "`last`, `avg` (-, iterations), `error` (-, relative to rho0)"});
}

}  // namespace pbf

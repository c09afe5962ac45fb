// iterations: what the constraint solver did. last = iterations of the last step; avg =
// their mean over the steps since this compute was last evaluated (a thermo line: the
// average since the previous line); error = the mean compression, mean of max(rho/rho0 - 1,
// 0), that pbf measured in its last iteration, before that iteration's correction (0 before
// the first step).
#include "engine/registry/builtin_styles.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

namespace {

class Iterations : public Compute {
 public:
  Iterations(const std::string& id, const Params&) : Compute(id, "iterations") {}
  std::vector<std::string> names() const override { return {"last", "avg", "error"}; }
  std::vector<std::string> units() const override { return {"-", "-", "-"}; }
  bool runs_distributed() const override { return true; }  // the solver's report is the same on every rank
  void evaluate(Simulation& sim, std::vector<double>& values) override {
    auto& report = sim.solver_report();
    const std::int64_t steps = report.steps - steps_seen_, sum = report.iteration_sum - sum_seen_;
    const double avg = steps > 0 ? double(sum) / double(steps) : double(report.iterations);
    steps_seen_ = report.steps;
    sum_seen_ = report.iteration_sum;
    values = {double(report.iterations), avg, report.error};
  }

 private:
  std::int64_t steps_seen_ = 0, sum_seen_ = 0;
};

}  // namespace

void register_compute_iterations(StyleRegistry& r) {
  r.add({"iterations", StyleKind::compute,
         "constraint iterations: last (of the last step), avg (since the previous evaluation), error (the mean "
         "compression pbf measured in the last iteration, before its correction)",
         {}, nullptr, make_compute<Iterations>(),
         "`last`, `avg` (-, iterations), `error` (-, relative to rho0)"});
}

}  // namespace pbf

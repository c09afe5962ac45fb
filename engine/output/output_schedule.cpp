#include "engine/output/output_schedule.hpp"

#include <spdlog/spdlog.h>

#include "engine/core/error.hpp"
#include "engine/io/bytes.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

std::vector<ParamSpec> OutputSchedule::params(const char* what) {
  return {ParamSpec{"interval", ParamType::Real, 0.0, "s", std::string("simulated time between ") + what +
                                                              " (or use 'every')"}
              .at_least(0),
          ParamSpec{"every", ParamType::Integer, std::int64_t{0}, "steps",
                    std::string("steps between ") + what + " (or use 'interval')"}
              .at_least(0)};
}

OutputSchedule::OutputSchedule(const Params& p, bool at_start)
    : interval_(p.real("interval")), every_(p.integer("every")), at_start_(at_start) {
  if ((interval_ > 0) == (every_ > 0)) throw Error("give exactly one of 'interval' (seconds) or 'every' (steps)");
}

void OutputSchedule::start(const Simulation& sim, const std::string& owner) {
  if (started_) return;
  started_ = true;
  start_time_ = sim.time();
  start_step_ = sim.step();
  const auto& plan = sim.run_plan();
  if (owner.empty()) return;
  if (every_ > 0 && static_cast<double>(every_) > plan.steps)
    spdlog::warn("{}: 'every' = {} steps is longer than the run ({:.0f} steps): no output after the start", owner,
                 every_, plan.steps);
  if (interval_ > 0 && start_time_ + interval_ > plan.end_time * (1 + 1e-9))
    spdlog::warn("{}: 'interval' = {} s is longer than the run ({} s): no output after the start", owner, interval_,
                 plan.end_time - start_time_);
}

bool OutputSchedule::due(const Simulation& sim) const {
  if (sim.step() == last_step_) return false;
  if (!at_start_ && sim.step() == start_step_) return false;
  if (at_start_ && count_ == 0) return true;  // the first output: the state the schedule starts from
  if (every_ > 0) return sim.step() % every_ == 0;
  const double next = static_cast<double>(count_ + (at_start_ ? 0 : 1)) * interval_;
  return sim.time() - start_time_ >= next * (1 - 1e-9);
}

void OutputSchedule::done(const Simulation& sim) {
  last_step_ = sim.step();
  ++count_;
}

void OutputSchedule::save(ByteWriter& w) const {
  w.put<std::uint8_t>(started_);
  w.put(start_time_);
  w.put(start_step_);
  w.put(count_);
  w.put(last_step_);
}

void OutputSchedule::restore(ByteReader& r) {
  started_ = r.get<std::uint8_t>() != 0;
  start_time_ = r.get<double>();
  start_step_ = r.get<std::int64_t>();
  count_ = r.get<std::int64_t>();
  last_step_ = r.get<std::int64_t>();
}

}  // namespace pbf

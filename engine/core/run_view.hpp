#pragma once
// A watcher of a run from outside the process (the browser's live view, engine/view/): after
// every step the run loop asks it what it wishes, and the wishes of all ranks are agreed in the
// one reduction Ctrl-C already uses (InterruptWatch::requested). Only rank 0 serves the view,
// so its wishes reach every rank, and all of them gather a frame, hold or stop after the same
// step: a clock or a socket read on each rank separately would have them disagree and deadlock.
#include <cstdint>
#include <string>

namespace pbf {

class Simulation;

// Numbers, so that a maximum over the ranks agrees them (the other ranks wish nothing: 0).
struct ViewWishes {
  double frame = 0;    // 1: gather a frame for the viewers now
  double pause = 0;    // 1: hold the run after this step
  double step = 0;     // 1: while held, one more step
  double field = 0;    // the colour field's index + 1 (0: unchanged)
  double picture = 0;  // 1: render a picture from the viewer's camera now
  static constexpr int kCount = 5;
  double* data() { return &frame; }
};
static_assert(sizeof(ViewWishes) == ViewWishes::kCount * sizeof(double));

class RunView {
 public:
  virtual ~RunView() = default;
  // A run starts at sim's step: to `last_step`, or (last_step < 0) to the time `end_time`.
  virtual void run_starts(Simulation& sim, std::int64_t last_step, double end_time) = 0;
  // This rank's wishes now (reading them takes them: a step or a picture is wished once).
  virtual ViewWishes wishes() = 0;
  // After the agreement, on every rank (may be collective): a frame, a picture, a new field.
  // `held`: the run is held after this step.
  virtual void act(Simulation& sim, const ViewWishes& agreed, bool held) = 0;
  // The run ended: `state` is "finished", "stopped" or "failed", `message` says more (the
  // restart written, the error).
  virtual void run_ends(Simulation& sim, const std::string& state, const std::string& message) = 0;
  // While held: waits up to `seconds` for a command from a viewer.
  virtual void wait(double seconds) = 0;
  // The port it serves on (rank 0; 0 on the others).
  virtual int port() const = 0;
};

}  // namespace pbf

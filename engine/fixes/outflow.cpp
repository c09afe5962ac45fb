// outflow: a sink. At the start of every step (the exchange stage) the particles inside its
// region are removed from the run: fluid that reaches a drain, the far end of a channel, the
// floor of a tank's orifice, leaves. What it removed, counted and weighed since the scene
// began, is the `flow` compute's to read (engine/core/particle_flow.hpp).
#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/core/particle_flow.hpp"
#include "engine/core/simulation.hpp"
#include "engine/geometry/region.hpp"
#include "engine/io/bytes.hpp"
#include "engine/registry/builtin_styles.hpp"

namespace pbf {

namespace {

class Outflow : public Fix {
 public:
  Outflow(const std::string& id, const Params& p) : Fix(id, "outflow"), region_(p) {}

  std::vector<Stage> stages() const override { return {Stage::exchange}; }
  bool runs_distributed() const override { return true; }  // each rank its own; the tally summed
  const ParticleFlow* particle_flow() const override { return &removed_; }
  bool removes_at(const real q[3]) const override { return region_.contains(q); }

  // (A solid's map is built in its own init, which may come after this one.)
  void init(Simulation&) override { checked_ = false; }

  void exchange(Simulation& sim) override {
    if (!checked_) region_.check_scene(sim);
    checked_ = true;
    auto& P = sim.particles();
    const std::size_t inside = region_.mark_inside(sim, drop_);
    if (inside == 0 && !P.distributed()) return;  // (on several ranks the counts are collective)
    removed_.count_marked(P, drop_);
    P.remove(drop_);
  }

  void save_state(ByteWriter& w) const override { removed_.save(w); }
  void restore_state(ByteReader& r) override { removed_.restore(r); }

 private:
  Region region_;
  ParticleFlow removed_;
  std::vector<char> drop_;  // kept: a step allocates nothing
  bool checked_ = false;
};

}  // namespace

void register_outflow(StyleRegistry& r) {
  r.add({"outflow", StyleKind::fix,
         "a sink: the particles inside its region leave the run at the start of every step (count and mass: the "
         "flow compute)",
         Region::params(), [](const std::string& id, const Params& p) { return std::make_unique<Outflow>(id, p); },
         nullptr});
}

}  // namespace pbf

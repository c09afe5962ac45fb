#pragma once
// What every dump style shares: a schedule (every K steps or every T simulated seconds,
// frame 0 at the start), a path pattern whose '*' becomes the frame number (five digits,
// zero-padded), the per-particle fields to write, and frame counters that restarts carry on.
// A style implements write_frame(); it runs in the end-of-step stage, after every other fix.
#include <string>

#include "engine/core/fix.hpp"
#include "engine/output/dump_fields.hpp"
#include "engine/output/path_pattern.hpp"
#include "engine/output/output_schedule.hpp"

namespace pbf {

class Dump : public Fix {
 public:
  // The shared parameters: path (pattern with '*'), fields (unless a style has no use for
  // them: pass none), interval, every.
  static std::vector<ParamSpec> params(const std::string& default_path, const Names& default_fields);

  Dump(const std::string& id, const std::string& style, const Params& p);

  std::vector<Stage> stages() const override { return {Stage::end_of_step}; }
  Role role() const override { return Role::output; }
  void init(Simulation& sim) override;
  void end_of_step(Simulation& sim) override;
  void save_state(ByteWriter& w) const override;
  void restore_state(ByteReader& r) override;

 protected:
  virtual void write_frame(Simulation& sim, const std::string& path, std::int64_t frame) = 0;
  std::string frame_path(std::int64_t frame) const;
  const std::string& pattern() const { return pattern_.pattern(); }
  std::string stem(const std::string& fallback) const { return pattern_.stem(fallback); }  // PathPattern::stem
  DumpFields& fields() { return fields_; }

 private:
  PathPattern pattern_;
  DumpFields fields_;
  OutputSchedule schedule_;
};

}  // namespace pbf

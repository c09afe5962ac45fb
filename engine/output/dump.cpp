#include "engine/output/dump.hpp"

#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

std::vector<ParamSpec> Dump::params(const std::string& default_path, const Names& default_fields) {
  std::vector<ParamSpec> p = {
      {"path", ParamType::String, default_path, "",
       "file name pattern; '*' becomes the frame number, 00000, 00001, ... (directories are created)"}};
  if (!default_fields.empty())
    p.push_back({"fields", ParamType::StringList, default_fields, "",
                 "per-particle fields: position, velocity, mass, id, density, density_error, summed_density, speed, "
                 "vorticity_magnitude, or any field a fix declares"});
  for (auto& s : OutputSchedule::params("frames")) p.push_back(std::move(s));
  return p;
}

Dump::Dump(const std::string& id, const std::string& style, const Params& p)
    : Fix(id, style), pattern_(p.string("path"), "the frame number"), fields_(p.has("fields") ? p.names("fields") : Names{}),
      schedule_(p, true) {
  if (p.has("fields") && fields_.size() == 0) throw Error("parameter 'fields' must name at least one field");
}

std::string Dump::frame_path(std::int64_t frame) const { return pattern_.with(fmt::format("{:05d}", frame)); }

void Dump::init(Simulation& sim) {
  fields_.resolve(sim);
  pattern_.create_directory();
  schedule_.start(sim, fmt::format("fix '{}' ({})", id(), style()));
  end_of_step(sim);  // frame 0: the state the run starts from
}

void Dump::end_of_step(Simulation& sim) {
  if (!schedule_.due(sim)) return;
  const std::string path = frame_path(schedule_.count());
  sim.outputs().wrote(fmt::format("{} of fix '{}' ({})", style() == "dump/image" ? "pictures" : "frames", id(), style()),
                      path);
  write_frame(sim, path, schedule_.count());
  schedule_.done(sim);
}

void Dump::save_state(ByteWriter& w) const { schedule_.save(w); }
void Dump::restore_state(ByteReader& r) { schedule_.restore(r); }

}  // namespace pbf

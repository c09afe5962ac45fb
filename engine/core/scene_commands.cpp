// The scene commands both bindings give (engine/core/scene_commands.hpp).
#include "engine/core/scene_commands.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <memory>

#include "engine/core/compute.hpp"
#include "engine/core/error.hpp"
#include "engine/core/simulation.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/geometry/mesh_file.hpp"
#include "engine/geometry/mesh_sdf.hpp"
#include "engine/geometry/mesh_surface.hpp"
#include "engine/geometry/region.hpp"
#include "engine/geometry/shape.hpp"
#include "engine/sph/lattice.hpp"

namespace pbf {

std::vector<ParamSpec> domain_params() {
  return {{"lo", ParamType::Vector3, std::nullopt, "m", ""},
          {"hi", ParamType::Vector3, std::nullopt, "m", ""},
          ParamSpec{"periodic", ParamType::StringList, Names{}, "", ""}.one_of({"x", "y", "z"})};
}

Domain domain_from(const Params& p) {
  Domain d;
  for (int a = 0; a < 3; ++a) {
    d.lo[a] = p.vec3("lo")[a];
    d.hi[a] = p.vec3("hi")[a];
  }
  for (const std::string& axis : p.names("periodic")) d.periodic[axis[0] - 'x'] = true;
  return d;
}

std::vector<ParamSpec> lattice_params() {
  return {{"lo", ParamType::Vector3, std::nullopt, "m", "", true},
          {"hi", ParamType::Vector3, std::nullopt, "m", "", true},
          {"spacing", ParamType::Real, std::nullopt, "m", ""},
          {"velocity", ParamType::Vector3, Vec3{0, 0, 0}, "m/s", ""},
          {"center", ParamType::Vector3, std::nullopt, "m", "", true},
          {"radius", ParamType::Real, 0.0, "m", ""},
          {"mesh", ParamType::String, std::nullopt, "", "", true},
          {"orient", ParamType::Bool, std::nullopt, "", "", true},
          ParamSpec{"scale", ParamType::Vector3, Vec3{1, 1, 1}, "", ""}.or_one_number(),
          {"rotate", ParamType::Vector3, Vec3{0, 0, 0}, "deg", ""},
          {"translate", ParamType::Vector3, Vec3{0, 0, 0}, "m", ""}};
}

LatticeAdded lattice_command(Simulation& sim, const Params& p, const char* what) {
  const Vec3 v = p.vec3("velocity");
  const double radius = p.real("radius");
  if (radius < 0 || (radius > 0) != p.has("center"))
    throw Error(fmt::format("{}: a sphere needs both 'center' and a positive 'radius'", what));
  if (radius > 0 && p.has("mesh")) throw Error(fmt::format("{}: give a sphere or a mesh, not both", what));
  if (p.has("orient") && !p.has("mesh")) throw Error(fmt::format("{}: 'orient' applies to a 'mesh' only", what));
  // The region: lo and hi, or the mesh's bounds (within the domain) where they are left out.
  std::unique_ptr<Shape> shape;
  Vec3 lo{}, hi{};
  if (p.has("mesh")) {
    const std::string& file = p.string("mesh");
    const double spacing = p.real("spacing");
    if (!(spacing > 0)) throw Error(fmt::format("{}: spacing must be positive, got {}", what, spacing));
    for (double factor : p.vec3("scale"))
      if (!(factor > 0 && factor <= 1e6))
        throw Error(fmt::format("{}: 'scale' must be in (0, 1e6], got {}", what, factor));
    TriangleMesh mesh = read_mesh_file(file);
    orient_surface(mesh, fmt::format("{}: mesh file '{}'", what, file), !p.has("orient") || p.boolean("orient"));
    Placement placement;
    placement.scale = p.vec3("scale");
    for (int a = 0; a < 3; ++a) {
      placement.rotate_deg[a] = p.vec3("rotate")[a];
      placement.translate[a] = p.vec3("translate")[a];
    }
    place(mesh, placement);
    const auto bounds_of_mesh = bounds(mesh);
    const Domain& domain = sim.domain();
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::max(bounds_of_mesh[0][a], domain.lo[a]);
      hi[a] = std::min(bounds_of_mesh[1][a], domain.hi[a]);
      if (!(hi[a] > lo[a]) && !(p.has("lo") && p.has("hi")))
        throw Error(fmt::format("{}: mesh file '{}' lies outside the domain: it spans [{:.6g}, {:.6g}] along "
                                "{}, the domain [{:.6g}, {:.6g}]",
                                what, file, bounds_of_mesh[0][a], bounds_of_mesh[1][a], "xyz"[a], domain.lo[a],
                                domain.hi[a]));
    }
    shape = mesh_shape(mesh, spacing / 2, 2 * spacing);
  } else if (radius > 0) {
    shape = sphere_shape({p.vec3("center")[0], p.vec3("center")[1], p.vec3("center")[2]}, radius, Placement{});
  }
  if (p.has("lo")) lo = p.vec3("lo");
  if (p.has("hi")) hi = p.vec3("hi");
  if (!shape && !(p.has("lo") && p.has("hi")))
    throw Error(fmt::format("{}: give 'lo' and 'hi' (or a 'mesh' to fill)", what));
  LatticeAdded result;
  result.first = sim.particles().size();
  result.added = add_lattice(sim, lo.data(), hi.data(), p.real("spacing"), v.data(), shape.get());
  return result;
}

std::vector<ParamSpec> delete_params() { return Region::params(); }

std::size_t delete_command(Simulation& sim, const Params& p) {
  Region region(p);
  region.check_scene(sim);
  std::vector<char> drop;
  region.mark_inside(sim, drop);
  std::size_t removed = sim.particles().remove(drop);
  if (sim.particles().distributed()) removed = static_cast<std::size_t>(comm::sum(static_cast<std::int64_t>(removed)));
  sim.positions_changed();
  return removed;
}

Compute& compute_to_evaluate(Simulation& sim, const std::string& id, const char* what) {
  Compute* c = sim.find_compute(id);
  if (!c) throw Error(fmt::format("{}: no compute with id '{}'", what, id));
  if (sim.global_count() == 0 && sim.particle_mass() == 0)  // (a drained scene has none, and is measured)
    throw Error(fmt::format("{}('{}'): there are no particles yet", what, id));
  if (sim.particles().distributed() && !c->runs_distributed())
    throw Error(fmt::format("{}('{}'): compute '{}' ({}) does not run on several MPI ranks yet", what, id, id,
                            c->style()));
  return *c;
}

}  // namespace pbf

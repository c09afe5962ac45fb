// solid, before a step: its parameters, the map it builds around its surface, the particles of
// a new scene it leaves out, its restart state and the pose its motion gives it. What it does
// in a step, and the equations, are in solid.cpp.
#include <algorithm>
#include <cmath>
#include <memory>
#include <omp.h>
#include <spdlog/spdlog.h>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/fixes/solid.hpp"
#include "engine/geometry/mesh_file.hpp"
#include "engine/io/bytes.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/sph/mass.hpp"

namespace pbf {

SolidFix::SolidFix(const std::string& id, const Params& p)
    : Fix(id, "solid"),
      shape_(id, p),
      fluid_inside_(p.string("fluid") == "inside"),
      friction_(p.real("friction")),
      no_slip_(p.boolean("no_slip")),
      wall_density_(p.boolean("wall_density")),
      motion_(p.has("motion") ? p.motion("motion") : nullptr) {
  contact_spacings_ = p.real("contact_distance");
  if (p.has("pivot")) {
    const Vec3 pivot = p.vec3("pivot");
    pivot_ = {pivot[0], pivot[1], pivot[2]};
  }
  if (SolidDynamics::wanted(p)) {
    if (shape_.is_plane()) throw Error("a plane cannot move (its map covers the domain only): use a box");
    dynamics_.emplace(id, p, shape_, fluid_inside_);
  } else {
    for (const auto& spec : SolidDynamics::params())
      if (p.has(spec.name))
        throw Error(fmt::format("parameter '{}' belongs to a body the fluid moves: give the solid a 'density' or a "
                                "'mass'",
                                spec.name));
  }
  if (motion_ && shape_.is_plane())
    throw Error("a plane cannot move (its map covers the domain only): use a box");
  if (!motion_ && p.has("pivot")) throw Error("'pivot' needs a 'motion'");
  surface_ = shape_.surface();
  std::string given;
  for (const auto& [name, value] : p.values()) given += (given.empty() ? "" : ", ") + name + " = " + format_value(value);
  description_ = given;
}

// The fastest any point of the solid moves from t to t + dt: rigid motion displaces the
// points of a box by an affine map, so the largest displacement is at a corner of the box
// around the placed surface.
double SolidFix::max_speed(double t, double dt) const {
  if (!moves() || !(dt > 0)) return 0;
  RigidTransform a, b;
  try {
    a = dynamics_ ? dynamics_->transform() : pose_at(t);
    b = dynamics_ ? dynamics_->after_step(t, dt) : pose_at(t + dt);
  } catch (const Error& e) {  // asked by time-step control: say whose motion it is
    throw Error(fmt::format("solid '{}': {}", id(), e.what()), e.located());
  }
  const auto box = bounds(shape_.surface());
  double most = 0;
  for (int k = 0; k < 8; ++k) {
    const Point corner{box[k & 1][0], box[(k >> 1) & 1][1], box[(k >> 2) & 1][2]};
    const Point p = a.apply(corner), q = b.apply(corner);
    most = std::max(most, std::hypot(q[0] - p[0], q[1] - p[1], q[2] - p[2]));
  }
  return most / dt;
}

// What the solid was made of, so a continued run can tell that it is the same solid: the
// mesh file's name and a hash of its bytes, the description of shape, placement and motion,
// and the pose it had when the restart was written.
void SolidFix::save_state(ByteWriter& w) const {
  w.put_string(description_);
  w.put_string(shape_.file());
  w.put<std::uint64_t>(shape_.file_hash());
  for (double v : pose_.translate) w.put(v);
  for (double v : pose_.rotate_deg) w.put(v);
  w.put<std::uint8_t>(dynamics_.has_value());
  if (dynamics_) dynamics_->save(w);
}

void SolidFix::restore_state(ByteReader& r) {
  const std::string description = r.get_string(), file = r.get_string();
  const auto hash = r.get<std::uint64_t>();
  Pose saved;
  for (double& v : saved.translate) v = r.get<double>();
  for (double& v : saved.rotate_deg) v = r.get<double>();
  saved_pose_ = saved;
  const bool body = r.get<std::uint8_t>() != 0;
  if (body != dynamics_.has_value())
    throw Error(fmt::format("solid '{}' is {} in the restart, and {} now: the run cannot continue from it", id(),
                            body ? "a body the fluid moves" : "no body", body ? "no body" : "a body"));
  if (dynamics_) dynamics_->restore(r);
  if (!file.empty() && file == shape_.file() && hash != shape_.file_hash())
    throw Error(fmt::format("solid '{}': mesh file '{}' has changed since the restart was written (its contents "
                            "differ): the continued run would not see the saved run's wall",
                            id(), file));
  if (description != description_)
    spdlog::warn("solid '{}' is not the restart's ({}; now {}): the run continues with the new one", id(),
                 description, description_);
}

void SolidFix::prepare_scene(Simulation& sim) {
  move_to(sim.time());
  prepare(sim);
  auto& P = sim.particles();
  real *x = P.x(), *y = P.y(), *z = P.z();
  // In a scene not yet stepped, a particle nearer than the contact distance would be put
  // back there by the first projection, and gain (gap - d) / dt of speed from it: a splash
  // at the start. One much nearer stands for volume that is partly inside the wall (whose
  // density counts from its surface), and is left out; one within a tenth of a spacing of
  // the contact distance (a lattice laid along the wall, read through the map's few
  // hundredths of a spacing of interpolation error) is moved out to it now, before it has a
  // velocity. Once the scene has run (a later run, a restart), only fluid inside the wall
  // is left out: the rest is the run's own, and is kept as it is, bit for bit.
  const bool fresh = sim.step() == 0;
  const real closest = fresh ? real(gap() - 0.1 * spacing_) : real(0), target = fresh ? real(gap()) : real(0);
  std::vector<char> drop(P.size(), 0);
  std::size_t moved = 0;
#pragma omp parallel for schedule(static) reduction(+ : moved)
  for (std::size_t i = 0; i < P.size(); ++i) {
    real d, g[3];
    const real q[3] = {x[i], y[i], z[i]};
    const auto where = distance_at(now_, q, d, g);
    drop[i] = where == SolidMap::Where::wall || (where == SolidMap::Where::near && d < closest);
    const real len = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    if (!drop[i] && where == SolidMap::Where::near && d < target && len > 0) {
      const real step = (target - d) / len;
      x[i] += step * g[0];
      y[i] += step * g[1];
      z[i] += step * g[2];
      ++moved;
    }
  }
  // (The others keep their ids; in a distributed run the counts are summed.)
  std::size_t removed = P.remove(drop);
  if (P.distributed()) {
    removed = static_cast<std::size_t>(comm::sum(static_cast<std::int64_t>(removed)));
    moved = static_cast<std::size_t>(comm::sum(static_cast<std::int64_t>(moved)));
  }
  if (removed > 0 && sim.global_count() == 0)
    throw Error(fmt::format("solid '{}' ({} it) leaves no particle: every one was created inside the wall", id(),
                            fluid_inside_ ? "fluid inside" : "fluid outside"));
  if (removed > 0)
    spdlog::info("solid '{}': left out {} particles created inside it or nearer than its contact distance", id(),
                 removed);
  if (moved > 0)
    spdlog::debug("solid '{}': moved {} particles out to its contact distance", id(), moved);
  if (removed > 0 || moved > 0) sim.positions_changed();  // (and any ghosts were dropped)
}

void SolidFix::init(Simulation& sim) {
  const Fix* integrator = sim.integrator();
  project_once_ = integrator && integrator->integration() == Integration::velocities;
  if (dynamics_) {  // every fix's acceleration of bodies (gravity)
    RigidBody::Vec g{0, 0, 0};
    for (const auto& fix : sim.fixes())
      for (int a = 0; a < 3; ++a) g[a] += fix->body_acceleration()[a];
    dynamics_->set_gravity(g);
    const auto solids = solids_of(sim);
    auto is_body = [](const SolidFix* s) { return s->dynamics_.has_value(); };
    steps_bodies_ = *std::find_if(solids.begin(), solids.end(), is_body) == this;
    settles_bodies_ = *std::find_if(solids.rbegin(), solids.rend(), is_body) == this;
    find_symmetry_planes(sim);
    first_step_ = sim.step();
  }
  move_to(sim.time());
  prepare(sim);
  viscous_no_slip_ = no_slip_ && wall_density_ && sim.max_kinematic_viscosity() > 0;
  if (saved_pose_ && motion_ && !(*saved_pose_ == pose_))
    spdlog::warn("solid '{}': its motion puts it elsewhere at t = {} than the restart saved it: the continued run "
                 "differs from the saved one", id(), sim.time());
  saved_pose_.reset();
}

// Builds the map when the scene it depends on (h, spacing, domain) changed. (Solvers call
// it within a step too: the pose stays the step's.)
void SolidFix::prepare(const Simulation& sim) {
  const bool changed = wall_.prepare(sim);
  if (no_slip_) viscous_.prepare(sim);
  const Domain& dom = sim.domain();
  const double key[7] = {sim.kernel_radius(), dom.lo[0], dom.lo[1], dom.lo[2], dom.hi[0], dom.hi[1], dom.hi[2]};
  if (!changed && built_ && std::equal(key, key + 7, built_for_)) return;
  std::copy(key, key + 7, built_for_);
  built_ = true;
  const double start = omp_get_wtime();
  const double h = sim.kernel_radius();
  spacing_ = lattice_spacing(sim.particle_mass(), sim.kernels(), sim.rest_density());
  const double cell = cell_size();
  const double reach = SolidMap::required_reach(h, cell, wall_.delta());
  const std::unique_ptr<Shape> shape = shape_.make_shape(dom, cell, reach);
  if (!moves()) surface_ = shape_.surface();  // a plane's is known now
  // A moving solid is queried in the frame it was placed in, over all of its surface.
  SolidMap::Region region{{dom.lo[0], dom.lo[1], dom.lo[2]}, {dom.hi[0], dom.hi[1], dom.hi[2]}, cell};
  if (moves()) {
    const auto box = bounds(shape_.surface());
    for (int a = 0; a < 3; ++a) {
      region.lo[a] = std::min(region.lo[a], box[0][a]);
      region.hi[a] = std::max(region.hi[a], box[1][a]);
    }
  }
  map_.build(*shape, fluid_inside_, region, wall_, sim.kernels());
  spdlog::info("solid '{}': {} triangles; density map of {} cells of {:.3g} m around the surface, built in {:.2f} s",
               id(), surface_.triangles.size(), map_.active_bricks() * 64, cell, omp_get_wtime() - start);
  if (!fluid_inside_ && !shape_.is_plane()) check_thickness(spacing_);
}

// Puts the solid where its motion has it at time t, a body where its state has it (the surface
// the outputs draw with it).
void SolidFix::move_to(double t, bool within_step) {
  if (dynamics_) place(dynamics_->transform());
  if (!motion_) return;
  try {
    pose_ = motion_->at(t);
  } catch (const Error& e) {
    if (!e.located() && within_step) throw;  // the run loop names the step and the fix
    throw Error(fmt::format("solid '{}': {}", id(), e.what()), e.located());
  }
  place(transform_of(pose_, pivot_));
}

void SolidFix::place(const RigidTransform& next) {
  if (next == now_ && surface_version_ > 0) return;
  now_ = next;
  const TriangleMesh& placed = shape_.surface();
  for (std::size_t k = 0; k < placed.vertices.size(); ++k) surface_.vertices[k] = now_.apply(placed.vertices[k]);
  ++surface_version_;
}

TriangleMesh SolidFix::surface_at(const RigidTransform& pose) const {
  if (pose == now_) return surface_;
  TriangleMesh moved = shape_.surface();
  for (auto& v : moved.vertices) v = pose.apply(v);
  return moved;
}

// The map's distance into the fluid, negated; deep in the wall and far in the fluid the map
// keeps only the side.
std::optional<double> SolidFix::depth_in_wall(const std::array<double, 3>& point) const {
  if (!built_ || moves()) return std::nullopt;
  real d = 0;
  switch (map_.distance(real(point[0]), real(point[1]), real(point[2]), d, nullptr)) {
    case SolidMap::Where::wall: return INFINITY;
    case SolidMap::Where::fluid: return -INFINITY;
    case SolidMap::Where::near: break;
  }
  return -double(d);
}

bool SolidFix::face_near(const std::array<double, 3>& point, double& distance, std::array<double, 3>& normal) const {
  if (!built_ || moves()) return false;
  real d = 0, grad[3];
  if (map_.distance(real(point[0]), real(point[1]), real(point[2]), d, grad) != SolidMap::Where::near) return false;
  const double length = std::sqrt(double(grad[0]) * grad[0] + double(grad[1]) * grad[1] + double(grad[2]) * grad[2]);
  if (!(length > 0)) return false;
  distance = d;
  for (int a = 0; a < 3; ++a) normal[a] = grad[a] / length;
  return true;
}

// An obstacle thinner than the particle spacing lets particles through between its nodes.
void SolidFix::check_thickness(double spacing) const {
  const double depth = map_.deepest();
  if (depth < 0.25 * spacing)
    throw Error(fmt::format("solid '{}' is at most about {:.3g} m thick, less than the particle spacing {:.3g} m: "
                            "particles would pass through it",
                            id(), 2 * depth + cell_size(), spacing));
}

// A body whose fastest point moves more than h in a step has blown up (the fluid it pushes
// would be thrown across its neighbourhood): stop with the body's state.
void SolidFix::check_body_speed(const Simulation& sim) const {
  const RigidBody& b = dynamics_->body();
  const RigidBody::Vec v = b.velocity(), w = b.angular_velocity();
  const double fastest = fastest_point_speed();
  if (fastest * sim.timestep() > sim.kernel_radius())
    throw Error(fmt::format("body '{}' blew up: a point of it moves {:.3g} m/s, more than h = {:.3g} m in one step "
                            "(velocity {:.4g} {:.4g} {:.4g} m/s, angular velocity {:.4g} {:.4g} {:.4g} rad/s)",
                            id(), fastest, sim.kernel_radius(), v[0], v[1], v[2], w[0], w[1], w[2]));
}

// A bound on the speed of the body's points: |v| + |w| R, R the farthest corner of the placed
// surface's box from the centre.
double SolidFix::fastest_point_speed() const {
  const RigidBody& b = dynamics_->body();
  const auto box = bounds(shape_.surface());
  const auto& c = dynamics_->placed_center();
  double reach = 0;
  for (int k = 0; k < 8; ++k)
    reach = std::max(reach, std::hypot(box[k & 1][0] - c[0], box[(k >> 1) & 1][1] - c[1], box[(k >> 2) & 1][2] - c[2]));
  const RigidBody::Vec v = b.velocity(), w = b.angular_velocity();
  return std::hypot(v[0], v[1], v[2]) + std::hypot(w[0], w[1], w[2]) * reach;
}

void register_solid(StyleRegistry& r) {
  const Vec3 zero{0, 0, 0};
  std::vector<ParamSpec> params = {ParamSpec{"shape", ParamType::String, std::string("mesh"), "", "what the solid is"}.one_of(
              {"mesh", "box", "sphere", "cylinder", "plane"}),
          ParamSpec{"file", ParamType::String, std::nullopt, "", "mesh file (OBJ, STL, ...) for shape 'mesh'", true},
          ParamSpec{"orient", ParamType::Bool, std::nullopt, "",
                    "shape 'mesh': turn triangles that face the wrong way (true, the default) or refuse them", true},
          ParamSpec{"fluid", ParamType::String, std::string("outside"), "",
                    "which side the fluid is on: outside (an obstacle) or inside (a container)"}
              .one_of({"outside", "inside"}),
          ParamSpec{"scale", ParamType::Vector3, Vec3{1, 1, 1}, "",
                    "scale about the origin: one number, or three for a mesh"}
              .above_within(0, 1e6)
              .or_one_number(),
          ParamSpec{"rotate", ParamType::Vector3, zero, "deg", "rotation about x, then y, then z (fixed axes)"}
              .magnitude_at_most(1e6),
          ParamSpec{"translate", ParamType::Vector3, zero, "m", "translation, after scale and rotation"}.magnitude_at_most(1e6),
          ParamSpec{"lo", ParamType::Vector3, std::nullopt, "m", "box: lower corner", true}.magnitude_at_most(1e6),
          ParamSpec{"hi", ParamType::Vector3, std::nullopt, "m", "box: upper corner", true}.magnitude_at_most(1e6),
          ParamSpec{"center", ParamType::Vector3, std::nullopt, "m", "sphere: centre", true}.magnitude_at_most(1e6),
          ParamSpec{"base", ParamType::Vector3, std::nullopt, "m", "cylinder: centre of the base", true}.magnitude_at_most(1e6),
          ParamSpec{"top", ParamType::Vector3, std::nullopt, "m", "cylinder: centre of the top", true}.magnitude_at_most(1e6),
          ParamSpec{"radius", ParamType::Real, std::nullopt, "m", "sphere, cylinder: radius", true}.above_within(0, 1e6),
          ParamSpec{"point", ParamType::Vector3, std::nullopt, "m", "plane: a point on it", true}.magnitude_at_most(1e6),
          ParamSpec{"normal", ParamType::Vector3, std::nullopt, "", "plane: its normal, pointing to the fluid", true}
              .magnitude_at_most(1e6),
          ParamSpec{"friction", ParamType::Real, 0.0, "1/s", "tangential velocity decay rate at the wall, exp(-rate dt)"}
              .at_least(0),
          {"no_slip", ParamType::Bool, false, "",
           "hold the fluid at the wall's velocity along it: through a Laplacian sph_viscosity's wall term (with "
           "wall_density), else by stopping a touching particle's tangential motion (overrides friction)"},
          {"wall_density", ParamType::Bool, true, "", "count the wall as fluid at rest density behind its surface"},
          ParamSpec{"contact_distance", ParamType::Real, 0.5, "spacing",
                    "closest a particle's centre comes to the surface, in particle spacings (0.5: its radius, "
                    "as the box's)"}
              .within(0, 2),
          ParamSpec{"motion", ParamType::Motion, std::nullopt, "",
                    "pose over time: function(t) returning {translate = {...}, rotate = {...}}, or pbf.keyframes{...}",
                    true},
          ParamSpec{"pivot", ParamType::Vector3, std::nullopt, "m",
                    "the point the motion's rotation turns about (default: the origin)", true}
              .magnitude_at_most(1e6)};
  for (auto& spec : SolidDynamics::params()) params.push_back(std::move(spec));
  r.add({"solid", StyleKind::fix,
         "a wall of any shape (mesh file or primitive), container or obstacle: density, projection, friction; a body "
         "the fluid moves, with a density or a mass",
         std::move(params), [](const std::string& id, const Params& p) { return std::make_unique<SolidFix>(id, p); },
         nullptr});
}

}  // namespace pbf

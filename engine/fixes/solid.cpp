// solid: a wall of any shape, from a mesh file (OBJ, STL, ...) or a primitive (box, sphere,
// cylinder, plane), holding the fluid in (a container) or keeping it out (an obstacle).
// It does what the box fix does at the domain faces, for any surface:
//  - density: the wall counts as fluid at rest density behind its surface; its share f(x)
//    of a particle's neighbourhood and grad f come from a map precomputed around the
//    surface (engine/geometry/solid_map.hpp). The solver adds rho0 f and rho0 grad f;
//  - projection: in every constraint iteration a particle that reached the wall is put back
//    `contact_distance` spacings in front of its surface (half a spacing by default, the
//    radius of the volume a particle stands for, as for the box); the path from where it
//    started the step is searched for the first contact, so a particle faster than a thin
//    wall is thick stops at the near side instead of being pushed out of the far one;
//  - after the velocity update, a particle on the wall loses its velocity into the wall and,
//    with friction, its tangential velocity at a rate per second (exp(-rate dt) per step),
//    or all of it with no_slip.
// Particles created inside the wall, or nearer to it than the contact distance, are left out
// at the start of the first run, with their count in the log (those within a tenth of a
// spacing of it are moved out to it instead); at later runs, those inside it.
// A solid may move (`motion`: a function of time or keyframes, engine/geometry/motion.hpp).
// The map stays in the frame where the scene placed the solid; a query at x in the world
// asks it at T(t)^-1 x, with T(t) the solid's pose. Over a step the wall goes from T0 = T(t)
// to T1 = T(t + dt): the step's path is searched in the wall's frame (from T0^-1 of the
// start to T1^-1 of the predicted position), so a wall that moves into a particle pushes it,
// and the wall's velocity at x is the motion of its point there, v_w = (x - T0 T1^-1 x) / dt:
// the fluid keeps no velocity into the wall relative to it, and friction acts on the
// tangential velocity relative to it.
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <omp.h>
#include <spdlog/spdlog.h>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/core/parallel.hpp"
#include "engine/core/simulation.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/io/bytes.hpp"
#include "engine/fixes/solid_shape.hpp"
#include "engine/geometry/mesh_file.hpp"
#include "engine/geometry/motion.hpp"
#include "engine/geometry/solid_map.hpp"
#include "engine/geometry/wall_contact.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/sph/density_boundary.hpp"
#include "engine/sph/mass.hpp"
#include "engine/sph/wall_density.hpp"

namespace pbf {

namespace {

class Solid : public Fix, public DensityBoundary, public SolidBody {
 public:
  Solid(const std::string& id, const Params& p)
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
    if (motion_ && shape_.is_plane())
      throw Error("a plane cannot move (its map covers the domain only): use a box");
    if (!motion_ && p.has("pivot")) throw Error("'pivot' needs a 'motion'");
    surface_ = shape_.surface();
    std::string given;
    for (const auto& [name, value] : p.values()) given += (given.empty() ? "" : ", ") + name + " = " + format_value(value);
    description_ = given;
  }

  std::vector<Stage> stages() const override {
    return {Stage::external_forces, Stage::constraints, Stage::velocity_update, Stage::end_of_step};
  }
  Role role() const override { return Role::boundary; }
  // Each particle meets the wall on its own; the load is summed over every rank's.
  bool runs_distributed() const override { return true; }
  DensityBoundary* density_boundary() override { return wall_density_ ? this : nullptr; }
  const SolidBody* solid_body() const override { return this; }
  const std::string& name() const override { return id(); }
  const TriangleMesh& surface() const override { return surface_; }
  std::uint64_t surface_version() const override { return surface_version_; }
  bool fluid_inside() const override { return fluid_inside_; }
  std::array<double, 6> load() const override { return load_; }
  void record_push(std::size_t i, const real momentum[3]) override {
    for (int c = 0; c < 3; ++c) push_[c][i] += momentum[c];
  }

  // The fastest any point of the solid moves from t to t + dt: rigid motion displaces the
  // points of a box by an affine map, so the largest displacement is at a corner of the box
  // around the placed surface.
  double max_speed(double t, double dt) const override {
    if (!motion_ || !(dt > 0)) return 0;
    RigidTransform a, b;
    try {
      a = pose_at(t);
      b = pose_at(t + dt);
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
  void save_state(ByteWriter& w) const override {
    w.put_string(description_);
    w.put_string(shape_.file());
    w.put<std::uint64_t>(shape_.file_hash());
    for (double v : pose_.translate) w.put(v);
    for (double v : pose_.rotate_deg) w.put(v);
  }

  void restore_state(ByteReader& r) override {
    const std::string description = r.get_string(), file = r.get_string();
    const auto hash = r.get<std::uint64_t>();
    Pose saved;
    for (double& v : saved.translate) v = r.get<double>();
    for (double& v : saved.rotate_deg) v = r.get<double>();
    saved_pose_ = saved;
    if (!file.empty() && file == shape_.file() && hash != shape_.file_hash())
      throw Error(fmt::format("solid '{}': mesh file '{}' has changed since the restart was written (its contents "
                              "differ): the continued run would not see the saved run's wall",
                              id(), file));
    if (description != description_)
      spdlog::warn("solid '{}' is not the restart's ({}; now {}): the run continues with the new one", id(),
                   description, description_);
  }

  void prepare_scene(Simulation& sim) override {
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
    // (In a distributed run the ids are renumbered across the ranks, and the counts summed.)
    std::size_t removed = P.remove(drop);
    if (P.distributed()) {
      removed = static_cast<std::size_t>(comm::sum(static_cast<std::int64_t>(removed)));
      moved = static_cast<std::size_t>(comm::sum(static_cast<std::int64_t>(moved)));
    }
    if (sim.global_count() == 0)
      throw Error(fmt::format("solid '{}' ({} it) leaves no particle: every one was created inside the wall", id(),
                              fluid_inside_ ? "fluid inside" : "fluid outside"));
    if (removed > 0)
      spdlog::info("solid '{}': left out {} particles created inside it or nearer than its contact distance", id(),
                   removed);
    if (moved > 0)
      spdlog::debug("solid '{}': moved {} particles out to its contact distance", id(), moved);
    if (removed > 0 || moved > 0) sim.positions_changed();  // (and any ghosts were dropped)
  }

  void init(Simulation& sim) override {
    move_to(sim.time());
    prepare(sim);
    if (saved_pose_ && motion_ && !(*saved_pose_ == pose_))
      spdlog::warn("solid '{}': its motion puts it elsewhere at t = {} than the restart saved it: the continued run "
                   "differs from the saved one", id(), sim.time());
    saved_pose_.reset();
  }

  // Builds the map when the scene it depends on (h, spacing, domain) changed. (Solvers call
  // it within a step too: the pose stays the step's.)
  void prepare(const Simulation& sim) override {
    const bool changed = wall_.prepare(sim);
    const Domain& dom = sim.domain();
    const double key[7] = {sim.kernel_radius(), dom.lo[0], dom.lo[1], dom.lo[2], dom.hi[0], dom.hi[1], dom.hi[2]};
    if (!changed && built_ && std::equal(key, key + 7, built_for_)) return;
    std::copy(key, key + 7, built_for_);
    built_ = true;
    const double start = omp_get_wtime();
    const double h = sim.kernel_radius();
    spacing_ = lattice_spacing(sim.particles().mean_mass(), sim.kernels(), sim.rest_density());
    const double cell = cell_size();
    const double reach = SolidMap::required_reach(h, cell, wall_.delta());
    const std::unique_ptr<Shape> shape = shape_.make_shape(dom, cell, reach);
    if (!motion_) surface_ = shape_.surface();  // a plane's is known now
    // A moving solid is queried in the frame it was placed in, over all of its surface.
    SolidMap::Region region{{dom.lo[0], dom.lo[1], dom.lo[2]}, {dom.hi[0], dom.hi[1], dom.hi[2]}, cell};
    if (motion_) {
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

  void add_density(const Simulation& sim, real x, real y, real z, std::size_t particle, real& rho,
                   real grad[3]) const override {
    real f, g[3];
    const real q[3] = {x, y, z};
    // Within a step, a particle still beyond the kernel's reach of a solid at rest (its start
    // distance less what it has moved since, and two cells for the spline's sharpening) sees
    // no wall: the map would answer f = 0.
    if (particle != kNoParticle && !motion_ && started_step_ == sim.step() && particle < start_distance_.size()) {
      const real moved = std::sqrt((x - start_[0][particle]) * (x - start_[0][particle]) +
                                   (y - start_[1][particle]) * (y - start_[1][particle]) +
                                   (z - start_[2][particle]) * (z - start_[2][particle]));
      if (far_from_wall(start_distance_[particle], moved, real(map_.far_distance() + 2 * cell_size()))) return;
    }
    if (fraction_at(now_, q, f, g) == SolidMap::Where::fluid) return;
    const real rho0 = real(sim.rest_density());
    rho += rho0 * f;
    for (int a = 0; a < 3; ++a) grad[a] += rho0 * g[a];
  }

  // The wall's velocity at q over the step: where that point of the wall was at the step's
  // start, to where it is at its end (now_, once external_forces has moved it).
  bool wall_velocity(const Simulation& sim, const real q[3], real v[3]) const override {
    if (!motion_) return false;
    const Point was = before_.apply(now_.apply_inverse({double(q[0]), double(q[1]), double(q[2])}));
    const double inv_dt = 1 / sim.timestep();
    for (int a = 0; a < 3; ++a) v[a] = real((q[a] - was[a]) * inv_dt);
    return true;
  }

  // Where each particle starts the step, in the wall's frame, and how far it is from the wall
  // there; the wall moves to where it is at the step's end.
  void external_forces(Simulation& sim) override {
    before_ = now_;
    move_to(sim.time() + sim.timestep(), true);
    const auto& P = sim.particles();
    const std::size_t n = P.size();
    for (auto& s : start_) s.resize(n);
    for (auto& s : push_) s.assign(n, 0);
    start_distance_.resize(n);
    started_step_ = sim.step();
    const real *x = P.x(), *y = P.y(), *z = P.z();
    const real far = real(map_.far_distance());  // far in the fluid: at least this far
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      const real q[3] = {x[i], y[i], z[i]};
      real b[3], d;
      to_frame(before_, q, b);
      for (int a = 0; a < 3; ++a) start_[a][i] = b[a];
      start_distance_[i] = map_.distance(b[0], b[1], b[2], d, nullptr) == SolidMap::Where::fluid ? far : d;
    }
  }

  void constraint(Simulation& sim, int) override {
    auto& P = sim.particles();
    real *x = P.x(), *y = P.y(), *z = P.z();
    const std::size_t n = P.size();
    std::size_t lost = n;
    // A solid touching a face of the domain (a ramp on the floor) may push a particle at its
    // foot across that face; the domain stays the hard limit.
    const Domain& dom = sim.domain();
    const real lo[3] = {real(dom.lo[0]), real(dom.lo[1]), real(dom.lo[2])};
    const real hi[3] = {real(dom.hi[0]), real(dom.hi[1]), real(dom.hi[2])};
    // Under an integrator of positions (pbf) a projection changes the velocity by dx / dt:
    // the wall takes m dx / dt. (A leapfrog's velocities are corrected in velocity_update.)
    const Fix* integrator = sim.integrator();
    const bool moves_momentum = integrator && integrator->integration() == Integration::positions;
    const real* m = P.mass();
    const real inv_dt = real(1 / sim.timestep());
#pragma omp parallel for schedule(static) reduction(min : lost)
    for (std::size_t i = 0; i < n; ++i) {
      real p[3] = {x[i], y[i], z[i]}, b[3];
      to_frame(now_, p, b);
      const real p0[3] = {start_[0][i], start_[1][i], start_[2][i]};
      const Contact contact = keep_out(map_, contact_distances(), p0, start_distance_[i], b);
      if (contact == Contact::lost) lost = std::min(lost, i);
      if (contact == Contact::moved) to_world(now_, b, p);
      for (int a = 0; a < 3; ++a) p[a] = std::clamp(p[a], lo[a], hi[a]);
      if (moves_momentum) {
        push_[0][i] += m[i] * (p[0] - x[i]) * inv_dt;
        push_[1][i] += m[i] * (p[1] - y[i]) * inv_dt;
        push_[2][i] += m[i] * (p[2] - z[i]) * inv_dt;
      }
      x[i] = p[0];
      y[i] = p[1];
      z[i] = p[2];
    }
    if (lost < n)
      throw Error(fmt::format("particle {} at ({}, {}, {}) went through solid '{}' at step {}{}", P.ids()[lost], x[lost],
                              y[lost], z[lost], id(), sim.step() + 1,
                              motion_ ? " (a moving wall needs a step that keeps its motion below the spacing: cfl)"
                                      : ""));
  }

  void velocity_update(Simulation& sim) override {
    auto& P = sim.particles();
    const real *x = P.x(), *y = P.y(), *z = P.z();
    real *vx = P.vx(), *vy = P.vy(), *vz = P.vz();
    const real keep = no_slip_ ? real(0) : real(std::exp(-friction_ * sim.timestep()));
    const real* m = P.mass();
    const real touching = real(contact_tolerance());
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < P.size(); ++i) {
      real d, g[3];
      const real q[3] = {x[i], y[i], z[i]};
      if (!motion_) {  // at rest, the step's start distance rules out most particles (keep_out)
        const real moved = std::sqrt((q[0] - start_[0][i]) * (q[0] - start_[0][i]) +
                                     (q[1] - start_[1][i]) * (q[1] - start_[1][i]) +
                                     (q[2] - start_[2][i]) * (q[2] - start_[2][i]));
        if (far_from_wall(start_distance_[i], moved, touching)) continue;
      }
      if (distance_at(now_, q, d, g) != SolidMap::Where::near || d > touching) continue;
      const real len = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
      if (len == 0) continue;
      const real nrm[3] = {g[0] / len, g[1] / len, g[2] / len};
      real wall[3] = {0, 0, 0};
      wall_velocity(sim, q, wall);
      const real rel[3] = {vx[i] - wall[0], vy[i] - wall[1], vz[i] - wall[2]};
      real vn = rel[0] * nrm[0] + rel[1] * nrm[1] + rel[2] * nrm[2];
      if (vn > 0) vn = 0;  // leaving the wall: keep it
      const real v[3] = {rel[0] - vn * nrm[0], rel[1] - vn * nrm[1], rel[2] - vn * nrm[2]};
      const real vt = v[0] * nrm[0] + v[1] * nrm[1] + v[2] * nrm[2];  // >= 0: the normal part kept
      real after[3];
      for (int a = 0; a < 3; ++a) after[a] = wall[a] + vt * nrm[a] + keep * (v[a] - vt * nrm[a]);
      push_[0][i] += m[i] * (after[0] - vx[i]);
      push_[1][i] += m[i] * (after[1] - vy[i]);
      push_[2][i] += m[i] * (after[2] - vz[i]);
      vx[i] = after[0];
      vy[i] = after[1];
      vz[i] = after[2];
    }
  }

  // The load of this step: the opposite of the momentum the wall gave the fluid, over dt
  // (deterministic sums), and its moment about the origin at the particles' positions.
  void end_of_step(Simulation& sim) override {
    const auto& P = sim.particles();
    const real *x = P.x(), *y = P.y(), *z = P.z();
    const real *px = push_[0].data(), *py = push_[1].data(), *pz = push_[2].data();
    const double inv_dt = 1 / sim.timestep();
    const std::size_t n = P.size();
    const bool ranks = P.distributed();
    load_[0] = -inv_dt * deterministic_sum(n, [&](std::size_t i) { return double(px[i]); }, ranks);
    load_[1] = -inv_dt * deterministic_sum(n, [&](std::size_t i) { return double(py[i]); }, ranks);
    load_[2] = -inv_dt * deterministic_sum(n, [&](std::size_t i) { return double(pz[i]); }, ranks);
    load_[3] = -inv_dt * deterministic_sum(n, [&](std::size_t i) { return double(y[i] * pz[i] - z[i] * py[i]); }, ranks);
    load_[4] = -inv_dt * deterministic_sum(n, [&](std::size_t i) { return double(z[i] * px[i] - x[i] * pz[i]); }, ranks);
    load_[5] = -inv_dt * deterministic_sum(n, [&](std::size_t i) { return double(x[i] * py[i] - y[i] * px[i]); }, ranks);
  }

 private:
  // Particles are kept a hair in front of the surface, above the map's rounding (a mesh's
  // distances are single precision), so that a wall on a face of the domain never leaves one
  // outside it; within twice the hair a particle touches the wall.
  double hair() const { return 1e-3 * cell_size(); }
  // Where projection puts a particle: `contact_distance` spacings in front of the surface,
  // and a hair more.
  double gap() const { return contact_spacings_ * spacing_ + hair(); }
  double contact_tolerance() const { return gap() + hair(); }
  double cell_size() const { return std::min(built_for_[0] / 4, spacing_ / 2); }

  RigidTransform pose_at(double t) const { return motion_ ? transform_of(motion_->at(t), pivot_) : RigidTransform{}; }

  // Puts the solid where its motion has it at time t (the surface the outputs draw with it).
  void move_to(double t, bool within_step = false) {
    if (!motion_) return;
    try {
      pose_ = motion_->at(t);
    } catch (const Error& e) {
      if (!e.located() && within_step) throw;  // the run loop names the step and the fix
      throw Error(fmt::format("solid '{}': {}", id(), e.what()), e.located());
    }
    const RigidTransform next = transform_of(pose_, pivot_);
    if (next == now_ && surface_version_ > 0) return;
    now_ = next;
    const TriangleMesh& placed = shape_.surface();
    for (std::size_t k = 0; k < placed.vertices.size(); ++k) surface_.vertices[k] = now_.apply(placed.vertices[k]);
    ++surface_version_;
  }

  // A world point in the frame the map was built in (the same point for a solid at rest), and back.
  void to_frame(const RigidTransform& T, const real q[3], real b[3]) const {
    if (!motion_) {
      std::copy(q, q + 3, b);
      return;
    }
    const Point p = T.apply_inverse({double(q[0]), double(q[1]), double(q[2])});
    for (int a = 0; a < 3; ++a) b[a] = real(p[a]);
  }
  void to_world(const RigidTransform& T, const real b[3], real q[3]) const {
    const Point p = T.apply({double(b[0]), double(b[1]), double(b[2])});
    for (int a = 0; a < 3; ++a) q[a] = real(p[a]);
  }
  // The map's answer at world point q with the solid at pose T: a gradient is turned back
  // into the world.
  SolidMap::Where distance_at(const RigidTransform& T, const real q[3], real& d, real g[3]) const {
    real b[3];
    to_frame(T, q, b);
    const auto where = map_.distance(b[0], b[1], b[2], d, g);
    if (motion_) rotate_to_world(T, g);
    return where;
  }
  SolidMap::Where fraction_at(const RigidTransform& T, const real q[3], real& f, real g[3]) const {
    real b[3];
    to_frame(T, q, b);
    const auto where = map_.fraction(b[0], b[1], b[2], f, g);
    if (motion_) rotate_to_world(T, g);
    return where;
  }
  static void rotate_to_world(const RigidTransform& T, real g[3]) {
    const Point r = T.rotate({double(g[0]), double(g[1]), double(g[2])});
    for (int a = 0; a < 3; ++a) g[a] = real(r[a]);
  }

  // Where projection puts particles, for keep_out (engine/geometry/wall_contact.hpp).
  ContactDistances contact_distances() const {
    return {real(hair()), real(gap()), real(0.25 * cell_size())};
  }

  // An obstacle thinner than the particle spacing lets particles through between its nodes.
  void check_thickness(double spacing) const {
    const double depth = map_.deepest();
    if (depth < 0.25 * spacing)
      throw Error(fmt::format("solid '{}' is at most about {:.3g} m thick, less than the particle spacing {:.3g} m: "
                              "particles would pass through it",
                              id(), 2 * depth + cell_size(), spacing));
  }

  SolidShape shape_;
  std::string description_;
  bool fluid_inside_;
  double friction_;
  bool no_slip_, wall_density_;
  MotionPtr motion_;  // nullptr: at rest
  Point pivot_{};
  Pose pose_;                           // where the motion has it now
  std::optional<Pose> saved_pose_;      // the restart's, until init compares
  RigidTransform before_, now_;         // its pose at the step's start and end (now)
  TriangleMesh surface_;                // the surface where it is now
  std::uint64_t surface_version_ = 0;

  HalfSpaceWall wall_;
  SolidMap map_;
  bool built_ = false;
  double built_for_[7] = {0, 0, 0, 0, 0, 0, 0};
  double spacing_ = 0, contact_spacings_ = 0;
  std::vector<real> start_[3], start_distance_;
  std::int64_t started_step_ = -1;  // the step start_ and start_distance_ belong to
  std::vector<real> push_[3];  // momentum the wall gave each particle in this step
  std::array<double, 6> load_{};
};

}  // namespace

void register_solid(StyleRegistry& r) {
  const Vec3 zero{0, 0, 0};
  r.add({"solid",
         StyleKind::fix,
         "a wall of any shape (mesh file or primitive), container or obstacle: density, projection, friction",
         {ParamSpec{"shape", ParamType::String, std::string("mesh"), "", "what the solid is"}.one_of(
              {"mesh", "box", "sphere", "cylinder", "plane"}),
          ParamSpec{"file", ParamType::String, std::nullopt, "", "mesh file (OBJ, STL, ...) for shape 'mesh'", true},
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
          {"no_slip", ParamType::Bool, false, "", "stop all tangential motion at the wall (overrides friction)"},
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
              .magnitude_at_most(1e6)},
         [](const std::string& id, const Params& p) { return std::make_unique<Solid>(id, p); }, nullptr});
}

}  // namespace pbf

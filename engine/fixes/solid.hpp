#pragma once
// The `solid` fix, internal to the engine: solid.cpp holds what it does in a step (the
// equations, at its top), solid_setup.cpp what it does before one (its parameters, its map,
// the scene's particles it leaves out, its restart state and its motion's pose).
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/core/simulation.hpp"
#include "engine/fixes/solid_dynamics.hpp"
#include "engine/fixes/solid_shape.hpp"
#include "engine/geometry/motion.hpp"
#include "engine/geometry/solid_map.hpp"
#include "engine/geometry/wall_contact.hpp"
#include "engine/sph/density_boundary.hpp"
#include "engine/sph/viscous_wall.hpp"
#include "engine/sph/wall_density.hpp"

namespace pbf {

struct BodyContact;

class SolidFix : public Fix, public DensityBoundary, public SolidBody {
 public:
  SolidFix(const std::string& id, const Params& p);

  std::vector<Stage> stages() const override {
    if (project_once_) return {Stage::external_forces, Stage::predict, Stage::velocity_update, Stage::end_of_step};
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
  const SolidDynamics* dynamics() const override { return dynamics_ ? &*dynamics_ : nullptr; }
  std::optional<double> depth_in_wall(const std::array<double, 3>& point) const override;
  bool face_near(const std::array<double, 3>& point, double& distance, std::array<double, 3>& normal) const override;
  void record_push(std::size_t i, const real momentum[3]) override {
    for (int c = 0; c < 3; ++c) push_[c][i] += momentum[c];
  }

  // Before a run (solid_setup.cpp).
  double max_speed(double t, double dt) const override;
  void save_state(ByteWriter& w) const override;
  void restore_state(ByteReader& r) override;
  void prepare_scene(Simulation& sim) override;
  void init(Simulation& sim) override;
  void prepare(const Simulation& sim) override;

  // In a step (solid.cpp).
  void add_density(const Simulation& sim, real x, real y, real z, std::size_t particle, real& rho,
                   real grad[3]) const override;
  bool wall_velocity(const Simulation& sim, const real q[3], real v[3]) const override;
  void add_moment(const Simulation& sim, const real q[3], std::size_t particle, real along,
                  real moment[6]) const override;
  bool no_slip() const override { return no_slip_; }
  void add_no_slip(const Simulation& sim, const real q[3], std::size_t particle, const real v[3],
                   real pull[3]) const override;
  void external_forces(Simulation& sim) override;
  // In every constraint iteration, after pbf's correction. Under dfsph (set in init, from the
  // pipeline), whose solves move velocities, not positions: once, right after its drift, so that
  // the neighbours and the solves see the positions the step keeps.
  void constraint(Simulation& sim, int) override { project(sim); }
  void predict(Simulation& sim) override { project(sim); }
  void velocity_update(Simulation& sim) override;
  void end_of_step(Simulation& sim) override;

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
  // Where projection puts particles, for keep_out (engine/geometry/wall_contact.hpp).
  ContactDistances contact_distances() const { return {real(hair()), real(gap()), real(0.25 * cell_size())}; }

  // Whether the particle (memory index), within a step, is still beyond the kernel's reach.
  bool out_of_reach(const Simulation& sim, std::size_t particle, const real q[3]) const;
  // Whether it moves: by its motion, or as a body the fluid moves.
  bool moves() const { return motion_ || dynamics_; }
  RigidTransform pose_at(double t) const { return motion_ ? transform_of(motion_->at(t), pivot_) : RigidTransform{}; }
  void move_to(double t, bool within_step = false);
  void place(const RigidTransform& T);
  void check_body_speed(const Simulation& sim) const;
  double fastest_point_speed() const;
  // Its pose at the simulation's time: a motion's then (whether or not its own stage has moved
  // it yet in this step), a body's or a resting solid's where it is; its surface there.
  RigidTransform pose_now(const Simulation& sim) const { return motion_ ? pose_at(sim.time()) : now_; }
  TriangleMesh surface_at(const RigidTransform& pose) const;

  // Bodies (solid_contact.cpp): the first body of the pipeline moves them all, contacts between.
  static std::vector<SolidFix*> solids_of(const Simulation& sim);
  void find_symmetry_planes(const Simulation& sim);
  void step_bodies(Simulation& sim);
  static void check_overlaps(const Simulation& sim, const std::vector<SolidFix*>& solids);
  static void set_pulls(const Simulation& sim, const std::vector<SolidFix*>& solids);
  static void resolve_contacts(const Simulation& sim, const std::vector<SolidFix*>& solids);
  void gather_contacts(const Simulation& sim, const std::vector<SolidFix*>& solids,
                       std::vector<BodyContact>& contacts);
  void check_thickness(double spacing) const;

  // A world point in the frame the map was built in (the same point for a solid at rest), and
  // back; the map's answers at a world point with the solid at pose T (solid.cpp).
  void to_frame(const RigidTransform& T, const real q[3], real b[3]) const;
  void to_world(const RigidTransform& T, const real b[3], real q[3]) const;
  using MapQuery = SolidMap::Where (SolidMap::*)(real, real, real, real&, real[3]) const;
  SolidMap::Where map_at(MapQuery query, const RigidTransform& T, const real q[3], real& value, real g[3]) const;
  SolidMap::Where distance_at(const RigidTransform& T, const real q[3], real& d, real g[3]) const {
    return map_at(&SolidMap::distance, T, q, d, g);
  }
  SolidMap::Where fraction_at(const RigidTransform& T, const real q[3], real& f, real g[3]) const {
    return map_at(&SolidMap::fraction, T, q, f, g);
  }

  SolidShape shape_;
  std::string description_;
  bool fluid_inside_;
  double friction_;
  bool no_slip_, wall_density_;
  bool viscous_no_slip_ = false;  // this run's: a Laplacian viscosity holds the no-slip wall
  MotionPtr motion_;  // nullptr: at rest, or a body
  std::optional<SolidDynamics> dynamics_;  // a body the fluid moves
  bool steps_bodies_ = false;              // the pipeline's first body: it moves them all
  bool settles_bodies_ = false;            // its last: it resolves contacts at the step's end
  std::int64_t first_step_ = 0;            // the run's first (its overlaps checked then)
  bool symmetry_[6] = {};                  // the domain faces it lies across (no contact there)
  Point pivot_{};
  Pose pose_;                           // where the motion has it now
  std::optional<Pose> saved_pose_;      // the restart's, until init compares
  RigidTransform before_, now_;         // its pose at the step's start and end (now)
  TriangleMesh surface_;                // the surface where it is now
  std::uint64_t surface_version_ = 0;

  HalfSpaceWall wall_;
  NoSlipWall viscous_;  // prepared with no_slip only
  SolidMap map_;
  bool built_ = false;
  double built_for_[7] = {0, 0, 0, 0, 0, 0, 0};
  double spacing_ = 0, contact_spacings_ = 0;
  bool project_once_ = false;  // this run's: under dfsph (see constraint)
  void project(Simulation& sim);
  std::vector<real> start_[3], start_distance_;
  std::int64_t started_step_ = -1;  // the step start_ and start_distance_ belong to
  std::vector<real> push_[3];  // momentum the wall gave each particle in this step
  std::array<double, 6> load_{};
};

}  // namespace pbf

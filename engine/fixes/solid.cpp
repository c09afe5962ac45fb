// solid: a wall of any shape, from a mesh file (OBJ, STL, ...) or a primitive (box, sphere,
// cylinder, plane), holding the fluid in (a container) or keeping it out (an obstacle).
// It does what the box fix does at the domain faces, for any surface:
//  - density: the wall counts as fluid at rest density behind its surface; its share f(x)
//    of a particle's neighbourhood and grad f come from a map precomputed around the
//    surface (engine/geometry/solid_map.hpp). The solver adds rho0 f and rho0 grad f;
//  - projection: in every constraint iteration (under dfsph once, after its drift) a particle
//    that reached the wall is put back `contact_distance` spacings in front of its surface
//    (half a spacing by default, the radius of the volume a particle stands for, as for the
//    box under pbf and wcsph); the path from where it
//    started the step is searched for the first contact, so a particle faster than a thin
//    wall is thick stops at the near side instead of being pushed out of the far one;
//  - after the velocity update, a particle on the wall loses its velocity into the wall and,
//    with friction, its tangential velocity at a rate per second (exp(-rate dt) per step),
//    or all of it with no_slip;
//  - no_slip under a Laplacian viscosity (sph_viscosity): instead of the touching particles'
//    velocity, the viscosity's wall term holds the fluid near the wall (to the wall's velocity),
//    the wall's fluid moving as Morris's boundary particles (engine/sph/viscous_wall.hpp) at
//    the flat wall's distance d_eff of the map's fraction; the solid takes its drag in its load.
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
// (The class is in solid.hpp; its construction, map, scene and restart state in solid_setup.cpp.)
#include <algorithm>
#include <limits>
#include <cmath>
#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/core/parallel.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/fixes/solid.hpp"

namespace pbf {

namespace {

// A gradient in the solid's frame, turned back into the world.
void rotate_to_world(const RigidTransform& T, real g[3]) {
  const Point r = T.rotate({double(g[0]), double(g[1]), double(g[2])});
  for (int a = 0; a < 3; ++a) g[a] = real(r[a]);
}

}  // namespace

void SolidFix::add_density(const Simulation& sim, real x, real y, real z, std::size_t particle, real& rho,
                           real grad[3]) const {
  real f, g[3];
  const real q[3] = {x, y, z};
  if (out_of_reach(sim, particle, q)) return;
  if (fraction_at(now_, q, f, g) == SolidMap::Where::fluid) return;
  const real rho0 = real(sim.rest_density());
  rho += rho0 * f;
  for (int a = 0; a < 3; ++a) grad[a] += rho0 * g[a];
}

// Within a step, a particle still beyond the kernel's reach of a solid at rest (its start
// distance less what it has moved since, and two cells for the spline's sharpening) sees no
// wall: the map would answer "far in the fluid".
bool SolidFix::out_of_reach(const Simulation& sim, std::size_t particle, const real q[3]) const {
  if (particle == kNoParticle || moves() || started_step_ != sim.step() || particle >= start_distance_.size())
    return false;
  const real moved = std::sqrt((q[0] - start_[0][particle]) * (q[0] - start_[0][particle]) +
                               (q[1] - start_[1][particle]) * (q[1] - start_[1][particle]) +
                               (q[2] - start_[2][particle]) * (q[2] - start_[2][particle]));
  return far_from_wall(start_distance_[particle], moved, real(map_.far_distance() + 2 * cell_size()));
}

// The no-slip wall's viscous pull (engine/sph/viscous_wall.hpp) at the flat wall's distance
// that gives the map's fraction, d_eff, along the normal grad d_eff: exact on a flat wall,
// and the wall's share of the neighbourhood kept at edges, corners and curves.
void SolidFix::add_no_slip(const Simulation& sim, const real q[3], std::size_t particle, const real v[3],
                           real pull[3]) const {
  real d, g[3];
  if (out_of_reach(sim, particle, q)) return;
  if (map_at(&SolidMap::effective_distance, now_, q, d, g) != SolidMap::Where::near) return;
  const real share = viscous_.share(d), len = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  if (share == 0 || len == 0) return;
  const real nrm[3] = {g[0] / len, g[1] / len, g[2] / len};
  real wall[3] = {0, 0, 0};
  wall_velocity(sim, q, wall);
  const real rel[3] = {wall[0] - v[0], wall[1] - v[1], wall[2] - v[2]};
  const real normal = rel[0] * nrm[0] + rel[1] * nrm[1] + rel[2] * nrm[2];
  for (int a = 0; a < 3; ++a) pull[a] += share * (rel[a] - normal * nrm[a]);
}

// The flat wall's moments (engine/sph/wall_density.hpp) at the distance d_eff that gives the
// map's fraction, about the normal grad d_eff, as for the no-slip pull.
void SolidFix::add_moment(const Simulation& sim, const real q[3], std::size_t particle, real along,
                          real moment[6]) const {
  real d, g[3];
  if (out_of_reach(sim, particle, q)) return;
  if (map_at(&SolidMap::effective_distance, now_, q, d, g) != SolidMap::Where::near) return;
  const real len = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  if (len == 0) return;
  const real n[3] = {g[0] / len, g[1] / len, g[2] / len}, rho0 = real(sim.rest_density());
  real normal, tangential;
  wall_.moments(d, normal, tangential);
  tangential *= along;
  const real across = rho0 * (normal - tangential);  // A n n + B (1 - n n) = B 1 + (A - B) n n
  for (int a = 0; a < 3; ++a) moment[a] += rho0 * tangential + across * n[a] * n[a];
  moment[3] += across * n[0] * n[1];
  moment[4] += across * n[0] * n[2];
  moment[5] += across * n[1] * n[2];
}

// The wall's velocity at q over the step: where that point of the wall was at the step's
// start, to where it is at its end (now_, once external_forces has moved it).
bool SolidFix::wall_velocity(const Simulation& sim, const real q[3], real v[3]) const {
  if (!moves()) return false;
  const Point was = before_.apply(now_.apply_inverse({double(q[0]), double(q[1]), double(q[2])}));
  const double inv_dt = 1 / sim.timestep();
  for (int a = 0; a < 3; ++a) v[a] = real((q[a] - was[a]) * inv_dt);
  return true;
}

// Where each particle starts the step, in the wall's frame, and how far it is from the wall
// there; the wall moves to where it is at the step's end.
void SolidFix::external_forces(Simulation& sim) {
  before_ = now_;
  if (dynamics_) {
    if (steps_bodies_) step_bodies(sim);
    place(dynamics_->transform());
  } else {
    move_to(sim.time() + sim.timestep(), true);
  }
  const auto& P = sim.particles();
  const std::size_t n = P.size();
  for (auto& s : start_) s.resize(n);
  for (auto& s : push_) s.assign(n, 0);
  start_distance_.resize(n);
  started_step_ = sim.step();
  const real *x = P.x(), *y = P.y(), *z = P.z();
  const real far = real(map_.far_distance());  // far in the fluid: at least this far
  for_particles(n, [&](std::size_t i) {
    const real q[3] = {x[i], y[i], z[i]};
    real b[3], d;
    to_frame(before_, q, b);
    for (int a = 0; a < 3; ++a) start_[a][i] = b[a];
    start_distance_[i] = map_.distance(b[0], b[1], b[2], d, nullptr) == SolidMap::Where::fluid ? far : d;
  });
}

void SolidFix::project(Simulation& sim) {
  auto& P = sim.particles();
  real *x = P.x(), *y = P.y(), *z = P.z();
  const std::size_t n = P.size();
  std::size_t lost = n;
  // A solid touching a face of the domain (a ramp on the floor) may push a particle at its
  // foot across that face; the domain stays the hard limit (but along a periodic axis, whose
  // faces a particle crosses to come back at the other side, and an open face, which it leaves
  // the run through).
  const Domain& dom = sim.domain();
  constexpr real kOpen = std::numeric_limits<real>::infinity();
  real lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    lo[a] = dom.periodic[a] || dom.open[2 * a] ? -kOpen : real(dom.lo[a]);
    hi[a] = dom.periodic[a] || dom.open[2 * a + 1] ? kOpen : real(dom.hi[a]);
  }
  // Under an integrator of positions (pbf) a projection changes the velocity by dx / dt:
  // the wall takes m dx / dt. (A leapfrog's velocities are corrected in velocity_update.)
  const bool moves_momentum = sim.integrator_moves_positions();
  const real* m = P.mass();
  const real inv_dt = real(1 / sim.timestep());
#pragma omp parallel for schedule(dynamic, kStreamBlock) reduction(min : lost)
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
                            moves() ? " (a moving wall needs a step that keeps its motion below the spacing: cfl)"
                                    : ""));
}

void SolidFix::velocity_update(Simulation& sim) {
  auto& P = sim.particles();
  const real *x = P.x(), *y = P.y(), *z = P.z();
  real *vx = P.vx(), *vy = P.vy(), *vz = P.vz();
  // (A no-slip wall that a Laplacian viscosity holds leaves the tangential velocity to it.)
  const real keep = no_slip_ && !viscous_no_slip_ ? real(0) : real(std::exp(-friction_ * sim.timestep()));
  const real* m = P.mass();
  // Under dfsph, whose pressure presses particles onto the wall, those the projection put at
  // the contact distance, which the map reads back within its interpolation error (a few
  // hundredths of a spacing), count as touching within a tenth of a spacing.
  const real touching = real(contact_tolerance() + (project_once_ ? 0.1 * spacing_ : 0));
  for_particles(P.size(), [&](std::size_t i) {
    real d, g[3];
    const real q[3] = {x[i], y[i], z[i]};
    if (!moves()) {  // at rest, the step's start distance rules out most particles (keep_out)
      const real moved = std::sqrt((q[0] - start_[0][i]) * (q[0] - start_[0][i]) +
                                   (q[1] - start_[1][i]) * (q[1] - start_[1][i]) +
                                   (q[2] - start_[2][i]) * (q[2] - start_[2][i]));
      if (far_from_wall(start_distance_[i], moved, touching)) return;
    }
    if (distance_at(now_, q, d, g) != SolidMap::Where::near || d > touching) return;
    const real len = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    if (len == 0) return;
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
  });
}

// The load of this step: the opposite of the momentum the wall gave the fluid, over dt
// (deterministic sums, in one pass), and its moment about the origin at the particles' positions.
void SolidFix::end_of_step(Simulation& sim) {
  const auto& P = sim.particles();
  const real *x = P.x(), *y = P.y(), *z = P.z();
  const real *px = push_[0].data(), *py = push_[1].data(), *pz = push_[2].data();
  const double inv_dt = 1 / sim.timestep();
  const std::size_t n = P.size();
  const bool ranks = P.distributed();
  const auto sums = deterministic_sums<6>(
      n,
      [&](std::size_t i) {
        return std::array<double, 6>{double(px[i]),
                                     double(py[i]),
                                     double(pz[i]),
                                     double(y[i] * pz[i] - z[i] * py[i]),
                                     double(z[i] * px[i] - x[i] * pz[i]),
                                     double(x[i] * py[i] - y[i] * px[i])};
      },
      ranks);
  for (int k = 0; k < 6; ++k) load_[k] = -inv_dt * sums[static_cast<std::size_t>(k)];
  if (dynamics_) {
    if (steps_bodies_) set_pulls(sim, solids_of(sim));  // the first body's end: none kicked yet
    dynamics_->end_step(load_, sim.timestep());
    check_body_speed(sim);
    if (settles_bodies_) resolve_contacts(sim, solids_of(sim));
  }
}

// A world point in the frame the map was built in (the same point for a solid at rest), and back.
void SolidFix::to_frame(const RigidTransform& T, const real q[3], real b[3]) const {
  if (!moves()) {
    std::copy(q, q + 3, b);
    return;
  }
  const Point p = T.apply_inverse({double(q[0]), double(q[1]), double(q[2])});
  for (int a = 0; a < 3; ++a) b[a] = real(p[a]);
}

void SolidFix::to_world(const RigidTransform& T, const real b[3], real q[3]) const {
  const Point p = T.apply({double(b[0]), double(b[1]), double(b[2])});
  for (int a = 0; a < 3; ++a) q[a] = real(p[a]);
}

// The map's answer (its distance or its fraction) at world point q with the solid at pose T:
// a gradient is turned back into the world.
SolidMap::Where SolidFix::map_at(MapQuery query, const RigidTransform& T, const real q[3], real& value,
                                 real g[3]) const {
  real b[3];
  to_frame(T, q, b);
  const auto where = (map_.*query)(b[0], b[1], b[2], value, g);
  if (moves()) rotate_to_world(T, g);
  return where;
}

}  // namespace pbf

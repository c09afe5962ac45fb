// solid: bodies meeting the walls and each other. The first body of the pipeline moves every
// body at the start of a step: each takes its half kick (solid_dynamics.cpp), then the contacts
// are resolved on the half-step velocities the drift is about to use, then each drifts.
//
// Contact points are the vertices of a body's surface; an obstacle is the domain's walls (a
// `box` fix's closed faces), a solid at rest (its map's distance), a solid a motion moves (its
// map at its pose now, its point moving at the pose's change over the coming step, u_w), or
// another body (its map, at its pose). A point at distance phi beyond the contact gap (one particle spacing: room for the
// layer of fluid both walls keep at half a spacing) along the obstacle's normal n is a contact
// when phi is within h. Speculative contacts (Catto's "sequential impulses"): the normal impulse
// lambda >= 0 makes the relative normal velocity
//   v_n >= -phi / dt              (phi >= 0: the drift may close the gap, not more; v_n relative
//                                  to the other body's point, or a moved solid's u_w)
//   v_n >= -beta phi / dt         (phi < 0: push out at beta = 0.2 of the overlap per step)
// with the impulse's effective mass 1 / K, K = n . dv per unit impulse at the point, summed over
// the two bodies (a body's locked axes and hinge respected). Coulomb friction limits the
// tangential impulse to mu lambda (mu: the bodies' contact_friction, the geometric mean of
// two). Sixteen Gauss-Seidel sweeps over the contacts in a fixed order: a body comes to rest on
// another without bouncing (no restitution) or sinking, and every rank computes the same bits.
//
// A face of the domain that a body's surface crosses or touches when the run starts is its
// symmetry plane (a half or quarter model), not a contact: the body must then keep still
// across it (its translation along the face's normal locked, no rotation but about that normal).
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <tuple>

#include "engine/core/error.hpp"
#include "engine/fixes/solid.hpp"
#include "engine/geometry/mesh_file.hpp"

namespace pbf {

using Vec = RigidBody::Vec;

namespace {

constexpr int kSweeps = 16;
constexpr double kPushOut = 0.2;

double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

}  // namespace

struct BodyContact {
  SolidDynamics* a;  // the body whose vertex touches (pushed along +n)
  SolidDynamics* b;  // the other body, or nullptr for a wall
  Vec p, n;
  double phi, K, mu;
  Vec wall{0, 0, 0};   // a wall's velocity at p (a solid a motion moves)
  double normal = 0;   // the impulses so far
  Vec tangential{0, 0, 0};
};

namespace {

Vec relative_velocity(const BodyContact& c) {
  Vec v = c.a->body().velocity_at(c.p);
  const Vec w = c.b ? c.b->body().velocity_at(c.p) : c.wall;
  for (int k = 0; k < 3; ++k) v[k] -= w[k];
  return v;
}

void push(BodyContact& c, const Vec& J) {
  c.a->push(J, c.p);
  if (c.b) c.b->push({-J[0], -J[1], -J[2]}, c.p);
}

double response(const BodyContact& c, const Vec& d) {
  return c.a->body().response(c.p, d) + (c.b ? c.b->body().response(c.p, d) : 0);
}

void sweep(std::vector<BodyContact>& contacts, double dt) {
  for (BodyContact& c : contacts) {
    const double v_min = c.phi >= 0 ? -c.phi / dt : -kPushOut * c.phi / dt;
    const double normal = std::max(c.normal + (v_min - dot(relative_velocity(c), c.n)) / c.K, 0.0);
    const double dn = normal - c.normal;
    c.normal = normal;
    push(c, {dn * c.n[0], dn * c.n[1], dn * c.n[2]});
    // Friction: against the sliding, within the cone mu lambda.
    const Vec v = relative_velocity(c);
    const double vn = dot(v, c.n);
    const Vec vt{v[0] - vn * c.n[0], v[1] - vn * c.n[1], v[2] - vn * c.n[2]};
    const double slide = std::sqrt(dot(vt, vt));
    if (slide == 0 || c.mu == 0) continue;
    const Vec t{vt[0] / slide, vt[1] / slide, vt[2] / slide};
    const double Kt = response(c, t);
    if (!(Kt > 0)) continue;
    Vec total{c.tangential[0] - slide / Kt * t[0], c.tangential[1] - slide / Kt * t[1],
              c.tangential[2] - slide / Kt * t[2]};
    const double size = std::sqrt(dot(total, total)), most = c.mu * c.normal;
    if (size > most)
      for (double& x : total) x *= most / size;
    push(c, {total[0] - c.tangential[0], total[1] - c.tangential[1], total[2] - c.tangential[2]});
    c.tangential = total;
  }
}

}  // namespace

std::vector<SolidFix*> SolidFix::solids_of(const Simulation& sim) {
  std::vector<SolidFix*> solids;
  for (const auto& fix : sim.fixes())
    if (auto* solid = dynamic_cast<SolidFix*>(fix.get())) solids.push_back(solid);
  return solids;
}

// The faces of the domain this body's placed surface crosses or touches: its symmetry planes.
void SolidFix::find_symmetry_planes(const Simulation& sim) {
  const Domain& dom = sim.domain();
  const auto box = bounds(shape_.surface());
  const RigidBody::Freedom& free = dynamics_->body().freedom();
  for (int a = 0; a < 3; ++a) {
    symmetry_[2 * a] = box[0][a] <= dom.lo[a] + hair();
    symmetry_[2 * a + 1] = box[1][a] >= dom.hi[a] - hair();
    if (!symmetry_[2 * a] && !symmetry_[2 * a + 1]) continue;
    const bool turns_off = free.turn == RigidBody::Freedom::Turn::free ||
                           (free.turn == RigidBody::Freedom::Turn::about_axis && free.axis != a);
    if (free.moves_along(a) || turns_off)
      throw Error(fmt::format("body '{}' reaches the domain face {} = {:.6g}, its symmetry plane: lock its translation "
                              "along {} (free_translation) and every rotation but about {} (free_rotation), or place "
                              "it clear of the face",
                              id(), "xyz"[a], symmetry_[2 * a] ? dom.lo[a] : dom.hi[a], "xyz"[a], "xyz"[a]));
  }
}

namespace {

// Points over a surface no farther apart than `step`: its vertices and, on each triangle, a
// barycentric grid fine enough for its longest edge.
std::vector<Point> surface_points(const TriangleMesh& mesh, double step) {
  std::vector<Point> points = mesh.vertices;
  for (const auto& t : mesh.triangles) {
    const Point &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    const double longest = std::max({std::hypot(b[0] - a[0], b[1] - a[1], b[2] - a[2]),
                                     std::hypot(c[0] - b[0], c[1] - b[1], c[2] - b[2]),
                                     std::hypot(a[0] - c[0], a[1] - c[1], a[2] - c[2])});
    const int k = std::min(200, int(std::ceil(longest / step)));
    for (int i = 0; i <= k; ++i)
      for (int j = 0; i + j <= k; ++j) {
        const double u = double(i) / k, v = double(j) / k, w = 1 - u - v;
        points.push_back({u * a[0] + v * b[0] + w * c[0], u * a[1] + v * b[1] + w * c[1], u * a[2] + v * b[2] + w * c[2]});
      }
  }
  return points;
}

}  // namespace

// At a run's first step (every solid's map built by then): no body may start inside a wall,
// a solid or another body (points over each surface half a spacing apart, tested against the
// other's map, both ways). A body's gap keeps it a spacing off them once it runs.
void SolidFix::check_overlaps(const Simulation& sim, const std::vector<SolidFix*>& solids) {
  auto inside = [&](const SolidFix& solid, const Point& p) {
    const real q[3] = {real(p[0]), real(p[1]), real(p[2])};
    real d, g[3];
    const auto where = solid.distance_at(solid.pose_now(sim), q, d, g);
    return where == SolidMap::Where::wall || (where == SolidMap::Where::near && d < 0);
  };
  for (const SolidFix* body : solids) {
    if (!body->dynamics_) continue;
    const auto points = surface_points(body->surface_, 0.5 * body->spacing_);
    for (const SolidFix* other : solids) {
      if (other == body) continue;
      const auto theirs = surface_points(other->surface_at(other->pose_now(sim)), 0.5 * body->spacing_);
      for (const auto& [from, into, list] : {std::tuple{body, other, &points}, std::tuple{other, body, &theirs}})
        for (const Point& p : *list)
          if (inside(*into, p))
            throw Error(fmt::format("body '{}' overlaps solid '{}': the point ({:.6g}, {:.6g}, {:.6g}) of {}'s surface "
                                    "lies inside {}; place the body clear of it",
                                    body->id(), other->id(), p[0], p[1], p[2], from->id(), into->id()));
    }
    const Domain& dom = sim.domain();
    for (const Point& v : body->surface_.vertices)
      for (int a = 0; a < 3; ++a)
        if ((v[a] < dom.lo[a] && !body->symmetry_[2 * a]) || (v[a] > dom.hi[a] && !body->symmetry_[2 * a + 1]))
          throw Error(fmt::format("body '{}' reaches outside the domain at ({:.6g}, {:.6g}, {:.6g})", body->id(), v[0],
                                  v[1], v[2]));
  }
}

// Every spring's pull on every body, from the bodies' states now (before any is kicked).
void SolidFix::set_pulls(const Simulation& sim, const std::vector<SolidFix*>& solids) {
  for (SolidFix* s : solids) {
    if (!s->dynamics_) continue;
    Vec force{0, 0, 0}, torque{0, 0, 0};
    for (const auto& fix : sim.fixes())
      if (const BodyForce* f = fix->body_force()) f->add_to(*s->dynamics_, force, torque);
    s->dynamics_->set_pull({force[0], force[1], force[2], torque[0], torque[1], torque[2]});
  }
}

void SolidFix::step_bodies(Simulation& sim) {
  const std::vector<SolidFix*> solids = solids_of(sim);
  if (sim.step() == first_step_) check_overlaps(sim, solids);
  set_pulls(sim, solids);
  for (SolidFix* s : solids)
    if (s->dynamics_) {
      s->dynamics_->begin_step(sim.time(), sim.timestep());
      s->check_body_speed(sim);
    }
  resolve_contacts(sim, solids);
  for (SolidFix* s : solids)
    if (s->dynamics_) s->dynamics_->drift(sim.timestep());
}

// The contacts of every moving body, resolved on its velocities now: at the start of a step
// (before the drift) and at its end, after the last kick, so that a body at rest on another
// reads a velocity of zero rather than the half kick of gravity the next step's contact takes back.
void SolidFix::resolve_contacts(const Simulation& sim, const std::vector<SolidFix*>& solids) {
  std::vector<BodyContact> contacts;
  for (SolidFix* s : solids)
    if (s->dynamics_ && s->dynamics_->moving()) s->gather_contacts(sim, solids, contacts);
  for (BodyContact& c : contacts) c.K = response(c, c.n);
  // A contact its bodies cannot answer (a point a joint holds still along n: K is zero but for
  // round-off, and 1 / K would throw the body) is the joint's to hold, not the contact's.
  std::erase_if(contacts, [](const BodyContact& c) {
    const double free = 1 / c.a->body().mass() + (c.b ? 1 / c.b->body().mass() : 0);
    return !(c.K > 1e-9 * free);
  });
  for (int k = 0; k < kSweeps && !contacts.empty(); ++k) sweep(contacts, sim.timestep());
}

// This body's vertices near the domain's closed walls, the solids at rest and the other bodies
// (a moving one only once per pair of vertex sets: its own vertices are gathered in its turn).
void SolidFix::gather_contacts(const Simulation& sim, const std::vector<SolidFix*>& solids,
                               std::vector<BodyContact>& contacts) {
  const Domain& dom = sim.domain();
  // A point is a contact when the step could close its gap: within twice what the two bodies'
  // fastest points cover in a step, and a twentieth of a spacing.
  const double gap = spacing_, dt = sim.timestep();
  const double own = fastest_point_speed() * dt, slack = 0.05 * spacing_;
  bool walls = false;
  for (const auto& fix : sim.fixes()) walls = walls || fix->style() == "box";
  const double mu = dynamics_->contact_friction();
  // The other solids whose surfaces come within reach of this one's (boxes around both).
  // (Each body moves at most h in a step, check_body_speed: a box 2 h wider holds them all.)
  auto near = bounds(surface_);
  for (int a = 0; a < 3; ++a) near[0][a] -= gap + 2 * sim.kernel_radius(), near[1][a] += gap + 2 * sim.kernel_radius();
  // A solid a motion moves: its pose now, and where that takes the point at p over the step.
  struct Other {
    SolidFix* solid;
    RigidTransform pose, next;
  };
  std::vector<Other> others;
  for (SolidFix* other : solids) {
    if (other == this) continue;
    const RigidTransform pose = other->pose_now(sim);
    const auto box = other->motion_ ? bounds(other->surface_at(pose)) : bounds(other->surface_);
    bool apart = false;
    for (int a = 0; a < 3; ++a) apart = apart || box[0][a] > near[1][a] || box[1][a] < near[0][a];
    if (!apart) others.push_back({other, pose, other->motion_ ? other->pose_at(sim.time() + dt) : pose});
  }
  for (const Point& vertex : surface_.vertices) {
    const Vec p{vertex[0], vertex[1], vertex[2]};
    for (int f = 0; walls && f < 6; ++f) {
      const int a = f / 2;
      if (symmetry_[f] || dom.open[f] || dom.periodic[a]) continue;
      const double phi = (f % 2 ? dom.hi[a] - p[a] : p[a] - dom.lo[a]) - gap;
      if (phi >= 2 * own + slack) continue;
      Vec n{0, 0, 0};
      n[static_cast<std::size_t>(a)] = f % 2 ? -1 : 1;
      contacts.push_back({&*dynamics_, nullptr, p, n, phi, 0, mu});
    }
    const real q[3] = {real(p[0]), real(p[1]), real(p[2])};
    for (const auto& [other, pose, next] : others) {
      real d, g[3];
      if (other->distance_at(pose, q, d, g) != SolidMap::Where::near) continue;
      const double phi = double(d) - gap, len = std::sqrt(double(g[0]) * g[0] + double(g[1]) * g[1] + double(g[2]) * g[2]);
      Vec wall{0, 0, 0};
      if (other->motion_) {
        const Point there = next.apply(pose.apply_inverse(vertex));
        for (int a = 0; a < 3; ++a) wall[a] = (there[a] - p[a]) / dt;
      }
      const double theirs = other->dynamics_ ? other->fastest_point_speed() * dt : std::sqrt(dot(wall, wall)) * dt;
      if (phi >= 2 * (own + theirs) + slack || len == 0) continue;
      SolidDynamics* b = other->dynamics_ && other->dynamics_->moving() ? &*other->dynamics_ : nullptr;
      const double pair_mu = other->dynamics_ ? std::sqrt(mu * other->dynamics_->contact_friction()) : mu;
      contacts.push_back({&*dynamics_, b, p, {g[0] / len, g[1] / len, g[2] / len}, phi, 0, pair_mu, wall});
    }
  }
}

}  // namespace pbf

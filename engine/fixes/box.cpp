// box: walls at the domain faces. Positions are projected into the box in every constraint
// iteration (after the solver's correction), to `contact_distance` spacings from each face
// (half a spacing by default: the radius of the volume a particle stands for keeps the first
// layer off the face, docs/physics.md "A column at rest"); after the velocity update, a particle touching
// a wall keeps -e times its incoming normal velocity and loses tangential velocity at a
// rate per second, exp(-rate dt) per step, so the friction a sliding front feels does not
// depend on the time step.
//
// With wall_density on, each face adds the density of the fluid-filled half-space behind it
// (engine/sph/wall_density.hpp). Faces combine as 1 - prod_k (1 - f_k): exact for one wall
// and close at edges and corners, where a plain sum would count the regions behind two walls
// twice. The solver adds rho0 times that and its gradient. Without it, particles near a wall
// miss part of their neighbourhood: the solver then packs them tighter, and the fluid sinks
// and sticks at the walls.
//
// With no_slip, the walls hold the fluid at rest along them. A Laplacian viscosity
// (sph_viscosity) does it through each face's viscous pull, Psi(d_k) (0 - v_i) along the
// face (engine/sph/viscous_wall.hpp), summed over the faces within reach (at an edge the
// region behind both faces counts for each); without one, a particle touching a face
// loses its velocity along it after the velocity update (friction without end), as a
// no-slip solid's does.
//
// An open face (`open`, e.g. {"x+"}) has no wall either: particles that cross it leave the
// run at the next step's start (the exchange stage), counted for the `flow` compute; the
// domain holds them beyond it until then (engine/core/domain.hpp).
//
// A periodic axis of the domain has no walls: its faces are where the fluid goes on (the
// periodic images, engine/core/periodic_images.hpp), so the box walls only the other axes.
#include <cmath>
#include <limits>
#include <vector>

#include <fmt/format.h>

#include "engine/sph/density_boundary.hpp"
#include "engine/core/error.hpp"
#include "engine/core/particle_flow.hpp"
#include "engine/io/bytes.hpp"
#include "engine/core/parallel.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/sph/mass.hpp"
#include "engine/sph/viscous_wall.hpp"
#include "engine/sph/wall_density.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

namespace {

// The closest a particle's centre comes to a face unless the script says, in particle
// spacings: 0.5, its radius, which keeps a column at rest still under pbf and wcsph; 0.25
// under an integrator of velocities (dfsph), whose walls' pressure holds the first layer where
// its density is rho0, a little nearer than half a spacing, so that the projection is a net
// below it instead of a second support the solve cannot see (docs/physics.md, "DFSPH at walls").
double default_contact_distance(const Simulation& sim) {
  const Fix* integrator = sim.integrator();
  return integrator && integrator->integration() == Integration::velocities ? 0.25 : 0.5;
}

class Box : public Fix, public DensityBoundary {
 public:
  Box(const std::string& id, const Params& p)
      : Fix(id, "box"),
        restitution_(p.real("restitution")),
        friction_(p.real("friction")),
        wall_density_(p.boolean("wall_density")),
        no_slip_(p.boolean("no_slip")),
        contact_given_(p.has("contact_distance")),
        contact_spacings_(contact_given_ ? p.real("contact_distance") : 0.5) {
    const Names& open = p.names("open");
    for (const std::string& face : open) {
      const int f = 2 * (face[0] - 'x') + (face[1] == '+');
      if (open_[f]) throw Error(fmt::format("parameter 'open' names face \"{}\" twice", face));
      open_[f] = true;
      any_open_ = true;
    }
  }

  std::vector<Stage> stages() const override {
    std::vector<Stage> stages;
    if (any_open_) stages.push_back(Stage::exchange);
    if (restitution_ > 0 || project_once_) stages.push_back(Stage::predict);
    if (!project_once_) stages.push_back(Stage::constraints);
    stages.push_back(Stage::velocity_update);
    return stages;
  }
  const ParticleFlow* particle_flow() const override { return any_open_ ? &left_ : nullptr; }
  std::array<bool, 6> open_faces() const override {
    std::array<bool, 6> faces;
    std::copy(open_, open_ + 6, faces.begin());
    return faces;
  }

  // The particles beyond an open face leave.
  void exchange(Simulation& sim) override {
    auto& P = sim.particles();
    const Domain& d = sim.domain();
    drop_.assign(P.size(), 0);
    std::size_t beyond = 0;
    for (std::size_t i = 0; i < P.size(); ++i) beyond += drop_[i] = d.beyond_open_face(P.x()[i], P.y()[i], P.z()[i]);
    if (beyond == 0 && !P.distributed()) return;  // (on several ranks the counts are collective)
    left_.count_marked(P, drop_);
    P.remove(drop_);
  }
  void save_state(ByteWriter& w) const override {
    if (any_open_) left_.save(w);
  }
  void restore_state(ByteReader& r) override {
    if (any_open_) left_.restore(r);
  }
  Role role() const override { return Role::boundary; }
  bool runs_distributed() const override { return true; }  // each particle on its own
  std::vector<const char*> exclusive_jobs() const override { return {"walls at the domain faces"}; }
  DensityBoundary* density_boundary() override { return wall_density_ ? this : nullptr; }

  // With restitution: the velocity each particle arrives with (within a step only). Under
  // dfsph (set in init, from the pipeline), whose solves move velocities, not positions: the
  // projection, once, right after its drift, so that the neighbours and the solves see the
  // positions the step keeps.
  void predict(Simulation& sim) override {
    const auto& P = sim.particles();
    if (restitution_ > 0) {
      const real* v[3] = {P.vx(), P.vy(), P.vz()};
      for (int c = 0; c < 3; ++c) incoming_[c].assign(v[c], v[c] + P.size());
    }
    if (project_once_) project(sim);
  }

  // In every constraint iteration, after pbf's correction.
  void constraint(Simulation& sim, int) override { project(sim); }

  // Positions back into the box, contact_ from each face.
  void project(Simulation& sim) {
    auto& P = sim.particles();
    const Domain& d = sim.domain();
    real *x = P.x(), *y = P.y(), *z = P.z();
    constexpr real kOpen = std::numeric_limits<real>::infinity();  // a periodic axis: no clamping
    real lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {  // (an open face: none either)
      lo[a] = d.periodic[a] || open_[2 * a] ? -kOpen : real(d.lo[a] + contact_);
      hi[a] = d.periodic[a] || open_[2 * a + 1] ? kOpen : real(d.hi[a] - contact_);
    }
    auto clamp = [](real v, real a, real b) { return v < a ? a : (v > b ? b : v); };
    for_particles(P.size(), [&](std::size_t i) {
      x[i] = clamp(x[i], lo[0], hi[0]);
      y[i] = clamp(y[i], lo[1], hi[1]);
      z[i] = clamp(z[i], lo[2], hi[2]);
    });
  }

  void velocity_update(Simulation& sim) override {
    auto& P = sim.particles();
    const Domain& d = sim.domain();
    const real* x[3] = {P.x(), P.y(), P.z()};
    real* v[3] = {P.vx(), P.vy(), P.vz()};
    const real keep = no_slip_ && !viscous_no_slip_ ? real(0) : real(std::exp(-friction_ * sim.timestep()));
    const real e = real(restitution_);
    const bool bounce = restitution_ > 0;
    for_particles(P.size(), [&](std::size_t i) {
      for (int a = 0; a < 3; ++a) {
        if (d.periodic[a]) continue;
        // side: -1 touching the lower face, +1 the upper one; a clamped position is exact.
        const int side = x[a][i] <= real(d.lo[a] + contact_) ? -1 : (x[a][i] >= real(d.hi[a] - contact_) ? 1 : 0);
        if (side == 0 || open_[2 * a + (side > 0)]) continue;
        const real arriving = bounce ? incoming_[a][i] : v[a][i];
        if (arriving * side > 0) v[a][i] = -e * arriving;  // moving into the wall
        v[(a + 1) % 3][i] *= keep;
        v[(a + 2) % 3][i] *= keep;
      }
    });
  }

  void init(Simulation& sim) override {
    const Fix* integrator = sim.integrator();
    project_once_ = integrator && integrator->integration() == Integration::velocities;
    if (wall_density_) prepare(sim);
    viscous_no_slip_ = no_slip_ && wall_density_ && sim.max_kinematic_viscosity() > 0;
    const double spacing = lattice_spacing(sim.particle_mass(), sim.kernels(), sim.rest_density());
    if (!contact_given_) contact_spacings_ = default_contact_distance(sim);
    contact_ = contact_spacings_ * spacing;
    const Domain& d = sim.domain();
    for (int a = 0; a < 3; ++a)
      if (d.periodic[a] && (open_[2 * a] || open_[2 * a + 1]))
        throw Error(fmt::format("parameter 'open': axis {} is periodic, so its faces are neither walls nor open (the "
                                "fluid goes on across them)",
                                "xyz"[a]));
    for (int a = 0; a < 3; ++a)
      if (!d.periodic[a] && 2 * contact_ >= d.extent(a))
        throw Error(fmt::format("contact_distance = {} spacings ({:.3g} m) leaves no room across the domain ({:.3g} m "
                                "along {})", contact_spacings_, contact_, d.extent(a), "xyz"[a]));
  }

  void prepare(const Simulation& sim) override {
    wall_.prepare(sim);
    if (no_slip_) viscous_.prepare(sim);
  }

  bool no_slip() const override { return no_slip_; }

  void add_no_slip(const Simulation& sim, const real q[3], std::size_t, const real v[3], real pull[3]) const override {
    const Domain& d = sim.domain();
    for (int a = 0; a < 3; ++a) {
      if (d.periodic[a]) continue;  // no walls across a periodic axis
      const real share = (open_[2 * a] ? real(0) : viscous_.share(q[a] - real(d.lo[a]))) +
                         (open_[2 * a + 1] ? real(0) : viscous_.share(real(d.hi[a]) - q[a]));
      if (share == 0) continue;
      pull[(a + 1) % 3] -= share * v[(a + 1) % 3];  // along the faces: the walls are at rest
      pull[(a + 2) % 3] -= share * v[(a + 2) % 3];
    }
  }

  // Each face's flat-wall moments, along its axis (normal) and the other two (tangential).
  void add_moment(const Simulation& sim, const real q[3], std::size_t, real along, real moment[6]) const override {
    const Domain& d = sim.domain();
    const real h = sim.kernels().h, rho0 = real(sim.rest_density());
    for (int a = 0; a < 3; ++a) {
      if (d.periodic[a]) continue;
      const real to_face[2] = {q[a] - real(d.lo[a]), real(d.hi[a]) - q[a]};
      for (int side = 0; side < 2; ++side) {
        if (open_[2 * a + side] || to_face[side] + wall_.delta() >= h) continue;
        real normal, tangential;
        wall_.moments(to_face[side], normal, tangential);
        for (int b = 0; b < 3; ++b) moment[b] += rho0 * (b == a ? normal : along * tangential);
      }
    }
  }

  void add_density(const Simulation& sim, real x, real y, real z, std::size_t, real& rho, real grad[3]) const override {
    const Domain& d = sim.domain();
    const real h = sim.kernels().h;
    const real p[3] = {x, y, z};
    real f[6], df[6];  // share of each face and its derivative along the face's axis
    real outside = 1;  // prod_k (1 - f_k)
    bool near = false;
    for (int a = 0; a < 3; ++a) {
      if (d.periodic[a]) {
        f[2 * a] = f[2 * a + 1] = df[2 * a] = df[2 * a + 1] = 0;
        continue;
      }
      const real to_lo = p[a] - real(d.lo[a]), to_hi = real(d.hi[a]) - p[a];
      f[2 * a] = !open_[2 * a] && to_lo + wall_.delta() < h ? wall_.fraction(to_lo, df[2 * a]) : (df[2 * a] = 0, real(0));
      f[2 * a + 1] = !open_[2 * a + 1] && to_hi + wall_.delta() < h ? wall_.fraction(to_hi, df[2 * a + 1])
                                                                       : (df[2 * a + 1] = 0, real(0));
      df[2 * a + 1] = -df[2 * a + 1];  // the distance to the upper face falls as x_a grows
      near = near || f[2 * a] > 0 || f[2 * a + 1] > 0;
      outside *= (1 - f[2 * a]) * (1 - f[2 * a + 1]);
    }
    if (!near) return;
    const real rho0 = real(sim.rest_density());
    rho += rho0 * (1 - outside);
    for (int k = 0; k < 6; ++k)
      if (df[k] != 0) grad[k / 2] += rho0 * outside / (1 - f[k]) * df[k];
  }

 private:
  HalfSpaceWall wall_;
  NoSlipWall viscous_;
  double restitution_, friction_;
  bool wall_density_, no_slip_;
  bool viscous_no_slip_ = false;  // this run's: a Laplacian viscosity holds the no-slip walls
  bool contact_given_;
  bool project_once_ = false;  // this run's: under dfsph (see predict)
  double contact_spacings_, contact_ = 0;  // in spacings, and in metres for this run
  std::vector<real> incoming_[3];
  bool open_[6] = {false, false, false, false, false, false}, any_open_ = false;  // faces x-, x+, y-, y+, z-, z+
  ParticleFlow left_;       // what left through the open faces
  std::vector<char> drop_;  // kept: a step allocates nothing
};

}  // namespace

void register_box(StyleRegistry& r) {
  r.add({"box",
         StyleKind::fix,
         "walls at the domain faces: projection, restitution, friction or no slip, wall density",
         {ParamSpec{"restitution", ParamType::Real, 0.0, "", "normal velocity kept after an impact, reversed"}.within(0, 1),
          ParamSpec{"friction", ParamType::Real, 0.0, "1/s", "tangential velocity decay rate at a wall, exp(-rate dt)"}
              .at_least(0),
          {"wall_density", ParamType::Bool, true, "",
           "count each wall as fluid at rest density behind it in the density sum"},
          {"no_slip", ParamType::Bool, false, "",
           "hold the fluid at rest along the walls: through a Laplacian sph_viscosity's wall term (with "
           "wall_density), else by stopping a touching particle's motion along the wall (overrides friction)"},
          ParamSpec{"open", ParamType::StringList, Names{}, "",
                    "faces with no wall, which particles leave the run through (count and mass: the flow compute)"}
              .one_of({"x-", "x+", "y-", "y+", "z-", "z+"}),
          ParamSpec{"contact_distance", ParamType::Real, std::nullopt, "spacing",
                    "closest a particle's centre comes to a face, in particle spacings (default 0.5, its radius, "
                    "which keeps a column at rest still, docs/physics.md; 0.25 under dfsph, whose walls' pressure "
                    "holds the fluid where its density is rho0)",
                    true}
              .within(0, 2)},
         [](const std::string& id, const Params& p) { return std::make_unique<Box>(id, p); }, nullptr});
}

}  // namespace pbf

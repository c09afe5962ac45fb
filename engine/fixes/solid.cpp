// solid: a wall of any shape, from a mesh file (OBJ, STL, ...) or a primitive (box, sphere,
// cylinder, plane), holding the fluid in (a container) or keeping it out (an obstacle).
// It does what the box fix does at the domain faces, for any surface:
//  - density: the wall counts as fluid at rest density behind its surface; its share f(x)
//    of a particle's neighbourhood and grad f come from a map precomputed around the
//    surface (engine/geometry/solid_map.hpp). The solver adds rho0 f and rho0 grad f;
//  - projection: in every constraint iteration a particle that reached the wall is put back
//    on its surface; the path from where it started the step is searched for the first
//    contact, so a particle faster than a thin wall is thick stops at the near side
//    instead of being pushed out of the far one;
//  - after the velocity update, a particle on the wall loses its velocity into the wall and,
//    with friction, its tangential velocity at a rate per second (exp(-rate dt) per step),
//    or all of it with no_slip.
// Particles created inside the wall are left out at the start of a run, with their count
// in the log.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <omp.h>
#include <spdlog/spdlog.h>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/core/parallel.hpp"
#include "engine/core/simulation.hpp"
#include "engine/io/bytes.hpp"
#include "engine/geometry/mesh_file.hpp"
#include "engine/geometry/mesh_sdf.hpp"
#include "engine/geometry/primitives.hpp"
#include "engine/geometry/solid_map.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/sph/density_boundary.hpp"
#include "engine/sph/mass.hpp"
#include "engine/sph/wall_density.hpp"

namespace pbf {

namespace {

double norm(const Point& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

// FNV-1a of a file's bytes (0 when it cannot be read: the mesh reader then says why).
std::uint64_t hash_of_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::uint64_t hash = 14695981039346656037ull;
  char buffer[65536];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    for (std::streamsize k = 0; k < in.gcount(); ++k) hash = (hash ^ static_cast<unsigned char>(buffer[k])) * 1099511628211ull;
    if (!in) break;
  }
  return hash;
}

class Solid : public Fix, public DensityBoundary, public SolidBody {
 public:
  Solid(const std::string& id, const Params& p)
      : Fix(id, "solid"),
        shape_name_(p.string("shape")),
        fluid_inside_(p.string("fluid") == "inside"),
        friction_(p.real("friction")),
        no_slip_(p.boolean("no_slip")),
        wall_density_(p.boolean("wall_density")) {
    const Vec3 scale = p.vec3("scale"), rotate = p.vec3("rotate"), translate = p.vec3("translate");
    for (int a = 0; a < 3; ++a) {
      placement_.scale[a] = scale[a];
      placement_.rotate_deg[a] = rotate[a];
      placement_.translate[a] = translate[a];
    }
    describe_shape(p);
    std::string given;
    for (const auto& [name, value] : p.values()) given += (given.empty() ? "" : ", ") + name + " = " + format_value(value);
    description_ = given;
  }

  std::vector<Stage> stages() const override {
    return {Stage::external_forces, Stage::constraints, Stage::velocity_update, Stage::end_of_step};
  }
  Role role() const override { return Role::boundary; }
  DensityBoundary* density_boundary() override { return wall_density_ ? this : nullptr; }
  const SolidBody* solid_body() const override { return this; }
  const std::string& name() const override { return id(); }
  const TriangleMesh& surface() const override { return surface_; }
  bool fluid_inside() const override { return fluid_inside_; }
  std::array<double, 6> load() const override { return load_; }
  void record_push(std::size_t i, const real momentum[3]) override {
    for (int c = 0; c < 3; ++c) push_[c][i] += momentum[c];
  }

  // What the solid was made of, so a continued run can tell that it is the same solid: the
  // mesh file's name and a hash of its bytes, and the description of shape and placement.
  void save_state(ByteWriter& w) const override {
    w.put_string(description_);
    w.put_string(file_);
    w.put<std::uint64_t>(file_hash_);
  }

  void restore_state(ByteReader& r) override {
    const std::string description = r.get_string(), file = r.get_string();
    const auto hash = r.get<std::uint64_t>();
    if (!file.empty() && file == file_ && hash != file_hash_)
      throw Error(fmt::format("solid '{}': mesh file '{}' has changed since the restart was written (its contents "
                              "differ): the continued run would not see the saved run's wall",
                              id(), file_));
    if (description != description_)
      spdlog::warn("solid '{}' is not the restart's ({}; now {}): the run continues with the new one", id(),
                   description, description_);
  }

  void prepare_scene(Simulation& sim) override {
    prepare(sim);
    auto& P = sim.particles();
    const real *x = P.x(), *y = P.y(), *z = P.z();
    std::vector<char> drop(P.size(), 0);
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < P.size(); ++i) {
      real d, g[3];
      const auto where = map_.distance(x[i], y[i], z[i], d, g);
      drop[i] = where == SolidMap::Where::wall || (where == SolidMap::Where::near && d < 0);
    }
    const std::size_t removed = P.remove(drop);
    if (P.size() == 0)
      throw Error(fmt::format("solid '{}' ({} it) leaves no particle: every one was created inside the wall", id(),
                              fluid_inside_ ? "fluid inside" : "fluid outside"));
    if (removed > 0) {
      spdlog::info("solid '{}': left out {} particles created inside it", id(), removed);
      sim.positions_changed();
    }
  }

  void init(Simulation& sim) override { prepare(sim); }

  // Builds the map when the scene it depends on (h, spacing, domain) changed.
  void prepare(const Simulation& sim) override {
    const bool changed = wall_.prepare(sim);
    const Domain& dom = sim.domain();
    const double key[7] = {sim.kernel_radius(), dom.lo[0], dom.lo[1], dom.lo[2], dom.hi[0], dom.hi[1], dom.hi[2]};
    if (!changed && built_ && std::equal(key, key + 7, built_for_)) return;
    std::copy(key, key + 7, built_for_);
    built_ = true;
    const double start = omp_get_wtime();
    const double h = sim.kernel_radius();
    const double spacing = lattice_spacing(sim.particles().mean_mass(), sim.kernels(), sim.rest_density());
    const double cell = std::min(h / 4, spacing / 2);
    const double reach = SolidMap::required_reach(h, cell, wall_.delta());
    if (!mesh_) primitive_ = make_primitive(dom);
    check_against_domain(dom, spacing);
    const std::unique_ptr<Shape> shape = mesh_ ? mesh_shape(surface_, cell, reach) : std::move(primitive_);
    SolidMap::Region region{{dom.lo[0], dom.lo[1], dom.lo[2]}, {dom.hi[0], dom.hi[1], dom.hi[2]}, cell};
    map_.build(*shape, fluid_inside_, region, wall_, sim.kernels());
    spdlog::info("solid '{}': {} triangles; density map of {} cells of {:.3g} m around the surface, built in {:.2f} s",
                 id(), surface_.triangles.size(), map_.active_bricks() * 64, cell, omp_get_wtime() - start);
    if (!fluid_inside_ && shape_name_ != "plane") check_thickness(spacing);
  }

  void add_density(const Simulation& sim, real x, real y, real z, real& rho, real grad[3]) const override {
    real f, g[3];
    if (map_.fraction(x, y, z, f, g) == SolidMap::Where::fluid) return;
    const real rho0 = real(sim.rest_density());
    rho += rho0 * f;
    for (int a = 0; a < 3; ++a) grad[a] += rho0 * g[a];
  }

  // Where each particle starts the step, and how far it is from the wall there.
  void external_forces(Simulation& sim) override {
    const auto& P = sim.particles();
    const std::size_t n = P.size();
    for (auto& s : start_) s.resize(n);
    for (auto& s : push_) s.assign(n, 0);
    start_distance_.resize(n);
    const real *x = P.x(), *y = P.y(), *z = P.z();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      start_[0][i] = x[i];
      start_[1][i] = y[i];
      start_[2][i] = z[i];
      real d, g[3];
      start_distance_[i] = map_.distance(x[i], y[i], z[i], d, g) == SolidMap::Where::fluid ? real(1e30) : d;
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
      real p[3] = {x[i], y[i], z[i]};
      if (!keep_out(i, p)) lost = std::min(lost, i);
      p[0] = std::clamp(p[0], lo[0], hi[0]);
      p[1] = std::clamp(p[1], lo[1], hi[1]);
      p[2] = std::clamp(p[2], lo[2], hi[2]);
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
      throw Error(fmt::format("particle {} at ({}, {}, {}) went through solid '{}' at step {}", P.ids()[lost], x[lost],
                              y[lost], z[lost], id(), sim.step() + 1));
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
      if (map_.distance(x[i], y[i], z[i], d, g) != SolidMap::Where::near || d > touching) continue;
      const real len = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
      if (len == 0) continue;
      const real nrm[3] = {g[0] / len, g[1] / len, g[2] / len};
      real vn = vx[i] * nrm[0] + vy[i] * nrm[1] + vz[i] * nrm[2];
      if (vn > 0) vn = 0;  // leaving the wall: keep it
      const real v[3] = {vx[i] - vn * nrm[0], vy[i] - vn * nrm[1], vz[i] - vn * nrm[2]};
      const real vt = v[0] * nrm[0] + v[1] * nrm[1] + v[2] * nrm[2];  // >= 0: the normal part kept
      const real after[3] = {vt * nrm[0] + keep * (v[0] - vt * nrm[0]), vt * nrm[1] + keep * (v[1] - vt * nrm[1]),
                             vt * nrm[2] + keep * (v[2] - vt * nrm[2])};
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
    load_[0] = -inv_dt * deterministic_sum(n, [&](std::size_t i) { return double(px[i]); });
    load_[1] = -inv_dt * deterministic_sum(n, [&](std::size_t i) { return double(py[i]); });
    load_[2] = -inv_dt * deterministic_sum(n, [&](std::size_t i) { return double(pz[i]); });
    load_[3] = -inv_dt * deterministic_sum(n, [&](std::size_t i) { return double(y[i] * pz[i] - z[i] * py[i]); });
    load_[4] = -inv_dt * deterministic_sum(n, [&](std::size_t i) { return double(z[i] * px[i] - x[i] * pz[i]); });
    load_[5] = -inv_dt * deterministic_sum(n, [&](std::size_t i) { return double(x[i] * py[i] - y[i] * px[i]); });
  }

 private:
  // Particles are kept a hair in front of the surface, above the map's rounding (a mesh's
  // distances are single precision), so that a wall on a face of the domain never leaves one
  // outside it; within twice the hair a particle touches the wall.
  double hair() const { return 1e-3 * cell_size(); }
  double contact_tolerance() const { return 2 * hair(); }
  double cell_size() const { return std::min(built_for_[0] / 4, spacing_ / 2); }

  // Moves p (particle i's position) out of the wall along the path it took this step. False
  // when the particle is deep inside the wall, which projection cannot undo.
  bool keep_out(std::size_t i, real p[3]) const {
    real d, g[3];
    const auto where = map_.distance(p[0], p[1], p[2], d, g);
    const real p0[3] = {start_[0][i], start_[1][i], start_[2][i]};
    const real step[3] = {p[0] - p0[0], p[1] - p0[1], p[2] - p0[2]};
    const real len = std::sqrt(step[0] * step[0] + step[1] * step[1] + step[2] * step[2]);
    const real hair = real(this->hair());
    const bool inside = where == SolidMap::Where::wall || (where == SolidMap::Where::near && d < hair / 2);
    if (!inside && len < start_distance_[i]) return true;  // cannot have reached the wall
    // March from the start: the first point at or behind the surface is where it met the wall.
    const real min_step = real(0.25 * cell_size());
    real s = 0, hit[3], dh = 0, gh[3];
    bool met = false;
    while (true) {
      for (int a = 0; a < 3; ++a) hit[a] = p0[a] + (len > 0 ? s / len : 0) * step[a];
      const auto w = map_.distance(hit[0], hit[1], hit[2], dh, gh);
      if (w == SolidMap::Where::wall) return false;
      if (w == SolidMap::Where::near && dh < hair / 2) {
        met = true;
        break;
      }
      if (s >= len) break;
      s = std::min(len, s + std::max(w == SolidMap::Where::fluid ? real(1e30) : dh, min_step));
    }
    if (!met) return true;  // passed near the wall without touching it
    // Take away the motion into the wall at the contact point, keep the motion along it.
    const real gl = std::sqrt(gh[0] * gh[0] + gh[1] * gh[1] + gh[2] * gh[2]);
    if (gl > 0) {
      // p's distance in front of the tangent plane at the contact
      const real into = ((p[0] - hit[0]) * gh[0] + (p[1] - hit[1]) * gh[1] + (p[2] - hit[2]) * gh[2]) / gl + dh;
      if (into < hair)
        for (int a = 0; a < 3; ++a) p[a] -= (into - hair) * gh[a] / gl;
    }
    // Onto the surface, a hair in front of it: Newton steps along the distance's gradient
    // (one for a flat wall).
    for (int it = 0; it < 4; ++it) {
      const auto w = map_.distance(p[0], p[1], p[2], d, g);
      if (w == SolidMap::Where::wall) return false;
      if (w == SolidMap::Where::fluid || d >= hair / 2) break;
      const real g2 = g[0] * g[0] + g[1] * g[1] + g[2] * g[2];
      if (g2 == 0) break;
      for (int a = 0; a < 3; ++a) p[a] -= (d - hair) * g[a] / g2;
    }
    return true;
  }

  void describe_shape(const Params& p) {
    // Each shape's own parameters; another shape's given here is a slip, refused.
    const std::vector<std::pair<std::string, std::vector<std::string>>> own = {
        {"mesh", {"file"}},
        {"box", {"lo", "hi"}},
        {"sphere", {"center", "radius"}},
        {"cylinder", {"base", "top", "radius"}},
        {"plane", {"point", "normal"}}};
    for (const auto& [shape, names] : own)
      for (const auto& name : names) {
        bool used = false;
        for (const auto& [mine, my_names] : own)
          used = used || (mine == shape_name_ && std::find(my_names.begin(), my_names.end(), name) != my_names.end());
        if (!used && p.has(name))
          throw Error(fmt::format("parameter '{}' does not apply to shape '{}' (it belongs to '{}')", name, shape_name_,
                                  shape));
      }
    auto need = [&](const char* name) {
      if (!p.has(name)) throw Error(fmt::format("shape '{}' needs the parameter '{}'", shape_name_, name));
      return p.vec3(name);
    };
    auto point = [](const Vec3& v) { return Point{v[0], v[1], v[2]}; };
    if (shape_name_ == "mesh") {
      if (!p.has("file")) throw Error("shape 'mesh' needs the parameter 'file' (an OBJ or STL file)");
      file_ = p.string("file");
      TriangleMesh mesh = read_mesh_file(file_);  // first: it refuses what is no mesh file (a device, a directory)
      file_hash_ = hash_of_file(file_);
      check_closed(mesh, fmt::format("mesh file '{}'", p.string("file")));
      orient_outward(mesh);
      place(mesh, placement_);
      surface_ = std::move(mesh);
      mesh_ = true;
      return;
    }
    if (shape_name_ == "box") {
      lo_ = point(need("lo"));
      hi_ = point(need("hi"));
      for (int a = 0; a < 3; ++a)
        if (!(hi_[a] > lo_[a])) throw Error(fmt::format("box: 'hi' must exceed 'lo' along {}", "xyz"[a]));
      surface_ = box_mesh(lo_, hi_);
    } else if (shape_name_ == "sphere" || shape_name_ == "cylinder") {
      if (!p.has("radius")) throw Error(fmt::format("shape '{}' needs the parameter 'radius'", shape_name_));
      radius_ = p.real("radius");
      if (shape_name_ == "sphere") {
        lo_ = point(need("center"));
        surface_ = sphere_mesh(lo_, radius_, radius_ / 8);
      } else {
        lo_ = point(need("base"));
        hi_ = point(need("top"));
        if (norm({hi_[0] - lo_[0], hi_[1] - lo_[1], hi_[2] - lo_[2]}) == 0)
          throw Error("cylinder: 'base' and 'top' are the same point");
        surface_ = cylinder_mesh(lo_, hi_, radius_, radius_ / 8);
      }
    } else {  // plane: its surface is drawn where it cuts the domain, known at the run
      lo_ = point(need("point"));
      hi_ = point(need("normal"));
      if (norm(hi_) == 0) throw Error("plane: 'normal' must not be zero");
      return;
    }
    place(surface_, placement_);
  }

  std::unique_ptr<Shape> make_primitive(const Domain& dom) {
    if (shape_name_ == "box") return box_shape(lo_, hi_, placement_);
    if (shape_name_ == "sphere") return sphere_shape(lo_, radius_, placement_);
    if (shape_name_ == "cylinder") return cylinder_shape(lo_, hi_, radius_, placement_);
    // A plane placed: its point and normal in the world, then an unplaced half-space.
    TriangleMesh marker;
    marker.vertices = {{lo_[0], lo_[1], lo_[2]}, {lo_[0] + hi_[0], lo_[1] + hi_[1], lo_[2] + hi_[2]}};
    place(marker, placement_);
    const Point at = marker.vertices[0];
    const Point normal{marker.vertices[1][0] - at[0], marker.vertices[1][1] - at[1], marker.vertices[1][2] - at[2]};
    surface_ = plane_patch(at, normal, {dom.lo[0], dom.lo[1], dom.lo[2]}, {dom.hi[0], dom.hi[1], dom.hi[2]});
    plane_point_ = at;
    plane_normal_ = normal;
    return plane_shape(at, normal, Placement{});
  }

  void check_against_domain(const Domain& dom, double spacing) {
    spacing_ = spacing;
    if (shape_name_ == "plane") {  // the half-space must reach into the domain
      bool touches = false;
      for (int k = 0; k < 8; ++k) {
        const Point corner{k & 1 ? dom.hi[0] : dom.lo[0], k & 2 ? dom.hi[1] : dom.lo[1], k & 4 ? dom.hi[2] : dom.lo[2]};
        touches = touches || (corner[0] - plane_point_[0]) * plane_normal_[0] + (corner[1] - plane_point_[1]) * plane_normal_[1] +
                                     (corner[2] - plane_point_[2]) * plane_normal_[2] <=
                                 0;
      }
      if (!touches)
        throw Error(fmt::format("solid '{}' lies outside the domain: the plane through ({:.6g}, {:.6g}, {:.6g}) leaves "
                                "the whole domain on its fluid side",
                                id(), plane_point_[0], plane_point_[1], plane_point_[2]));
      return;
    }
    const auto b = bounds(surface_);
    for (int a = 0; a < 3; ++a)
      if (b[0][a] > dom.hi[a] || b[1][a] < dom.lo[a])
        throw Error(fmt::format("solid '{}' lies outside the domain: it spans [{:.6g}, {:.6g}] along {}, the domain "
                                "[{:.6g}, {:.6g}]",
                                id(), b[0][a], b[1][a], "xyz"[a], dom.lo[a], dom.hi[a]));
  }

  // An obstacle thinner than the particle spacing lets particles through between its nodes.
  void check_thickness(double spacing) const {
    const double depth = map_.deepest();
    if (depth < 0.25 * spacing)
      throw Error(fmt::format("solid '{}' is at most about {:.3g} m thick, less than the particle spacing {:.3g} m: "
                              "particles would pass through it",
                              id(), 2 * depth + cell_size(), spacing));
  }

  std::string shape_name_, description_;
  std::string file_;             // the mesh file ("" for a primitive)
  std::uint64_t file_hash_ = 0;  // FNV-1a of its bytes
  bool fluid_inside_;
  double friction_;
  bool no_slip_, wall_density_;
  Placement placement_;
  Point lo_{}, hi_{};  // the primitive's two points (box corners, sphere centre, cylinder ends, plane point and normal)
  double radius_ = 0;
  Point plane_point_{}, plane_normal_{};  // a plane's, placed in the world
  bool mesh_ = false;
  TriangleMesh surface_;
  std::unique_ptr<Shape> primitive_;  // between its making and the map's build

  HalfSpaceWall wall_;
  SolidMap map_;
  bool built_ = false;
  double built_for_[7] = {0, 0, 0, 0, 0, 0, 0};
  double spacing_ = 0;
  std::vector<real> start_[3], start_distance_;
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
          {"wall_density", ParamType::Bool, true, "", "count the wall as fluid at rest density behind its surface"}},
         [](const std::string& id, const Params& p) { return std::make_unique<Solid>(id, p); }, nullptr});
}

}  // namespace pbf

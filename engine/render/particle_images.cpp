#include "engine/render/particle_images.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/sph/mass.hpp"
#include "engine/core/simulation.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/surface/scene_surface.hpp"

namespace pbf {

std::vector<ParamSpec> ParticleImages::params() {
  return {
      {"color", ParamType::String, std::string("speed"), "",
       "field that sets the colour (a dump field; a vector field is coloured by its magnitude)"},
      ParamSpec{"colormap", ParamType::String, std::string("viridis"), "", "colour map"}.one_of(Colormap::names()),
      {"min", ParamType::Real, 0.0, "field unit", "value at the bottom of the colour scale (min = max: each frame's range)"},
      {"max", ParamType::Real, 0.0, "field unit", "value at the top of the colour scale"},
      ParamSpec{"width", ParamType::Integer, std::int64_t{800}, "pixels", "image width"}.within(16, 8192),
      ParamSpec{"height", ParamType::Integer, std::int64_t{600}, "pixels", "image height"}.within(16, 8192),
      {"direction", ParamType::Vector3, Vec3{1, 2, -1}, "", "view direction, from the camera toward the centre"},
      {"up", ParamType::Vector3, Vec3{0, 0, 1}, "", "the direction that points up in the image"},
      {"center", ParamType::Vector3, std::nullopt, "m", "point the camera looks at (default: the domain's centre)", true},
      {"position", ParamType::Vector3, std::nullopt, "m",
       "camera position, looking at the centre ('direction' is then unused; default: back along 'direction', "
       "far enough to see the whole domain)",
       true},
      ParamSpec{"zoom", ParamType::Real, 1.0, "", "magnification; 1 shows the whole domain"}.above(0),
      ParamSpec{"radius", ParamType::Real, 0.0, "m", "sphere radius drawn per particle (0: 0.55 of the particle spacing)"}
          .at_least(0),
      {"box", ParamType::Bool, true, "", "draw the domain's edges"},
      {"colorbar", ParamType::Bool, true, "", "draw the labelled colour bar"},
      {"axes", ParamType::Bool, true, "", "draw the axis triad at the bottom left"},
      {"scale_bar", ParamType::Bool, true, "", "draw a scale bar at the bottom right, where one fits"},
      {"solids", ParamType::Bool, true, "",
       "draw the solids' surfaces (grey; a container shows its inside, its near walls left out)"},
      ParamSpec{"draw", ParamType::String, std::string("spheres"), "",
                "what the fluid looks like: spheres (each particle, coloured by 'color') or surface (the water's "
                "surface as dump/surface makes it, shaded as water; no colour bar)"}
          .one_of({"spheres", "surface"})};
}

ParticleImages::ParticleImages(const Params& p) : color_(Names{p.string("color")}), min_(p.real("min")), max_(p.real("max")) {
  if (min_ > max_) throw Error(fmt::format("'min' ({}) must not exceed 'max' ({})", min_, max_));
  spec_.width = static_cast<int>(p.integer("width"));
  spec_.height = static_cast<int>(p.integer("height"));
  spec_.direction = p.vec3("direction");
  spec_.up = p.vec3("up");
  if (p.has("center")) spec_.center = p.vec3("center");
  if (p.has("position")) spec_.eye = p.vec3("position");
  spec_.zoom = p.real("zoom");
  spec_.radius = p.real("radius");
  spec_.colormap = p.string("colormap");
  spec_.draw_box = p.boolean("box");
  spec_.colorbar = p.boolean("colorbar");
  spec_.axes = p.boolean("axes");
  spec_.scale_bar = p.boolean("scale_bar");
  draw_solids_ = p.boolean("solids");
  draw_surface_ = p.string("draw") == "surface";
  if (draw_surface_) spec_.colorbar = false;  // the water has no colour scale
  // A placeholder radius checks every other parameter (and loads the font) now, at pbf.fix.
  ImageSpec check = spec_;
  if (check.radius == 0) check.radius = 1;
  ImageRenderer{check};
}

void ParticleImages::init(Simulation& sim) {
  color_.resolve(sim);
  if (spec_.radius == 0) {
    spec_.radius = 0.55 * lattice_spacing(sim.particle_mass(), sim.kernels(), sim.rest_density());
  }
  const std::string unit = color_.unit(0);
  spec_.label = color_.components(0) == 1 ? color_.names()[0] : "|" + color_.names()[0] + "|";
  if (!unit.empty()) spec_.label += " (" + unit + ")";
  renderer_.emplace(spec_);
}

// The value a particle is coloured by: the field, or a vector field's magnitude.
double ParticleImages::colour_value(const real* values, int components) {
  double s = 0;
  for (int c = 0; c < components; ++c) s += double(values[c]) * double(values[c]);
  return components == 1 ? double(values[0]) : std::sqrt(s);
}

// Every particle's position and colour value in id order, on this process.
std::size_t ParticleImages::collect(Simulation& sim) {
  const std::size_t n = sim.particles().size();
  color_.gather(sim, 0, values_);
  DumpFields position(Names{"position"});
  position.resolve(sim);
  position.gather(sim, 0, positions_);
  const int nc = color_.components(0);
  scalar_.resize(n);
  for (std::size_t i = 0; i < n; ++i) scalar_[i] = colour_value(&values_[i * nc], nc);
  return n;
}

// A distributed run: every rank's particles gathered on rank 0, in id order (one picture, the
// same as one process draws). Returns the count on rank 0, 0 elsewhere.
std::size_t ParticleImages::collect_on_root(Simulation& sim) {
  sim.refresh_neighbors();  // a derived colour reads neighbours: the ghosts first (they move the arrays)
  const auto& P = sim.particles();
  const std::vector<const real*> columns = color_.columns(sim, 0);
  struct Record {
    std::int64_t id;
    real x, y, z;
    double value;
  };
  std::vector<Record> mine(P.size());
  std::vector<real> v(columns.size());
  for (std::size_t i = 0; i < P.size(); ++i) {
    for (std::size_t c = 0; c < columns.size(); ++c) v[c] = columns[c][i];
    mine[i] = {P.ids()[i], P.x()[i], P.y()[i], P.z()[i], colour_value(v.data(), static_cast<int>(v.size()))};
  }
  const auto gathered = comm::gather_bytes(
      std::span<const char>(reinterpret_cast<const char*>(mine.data()), mine.size() * sizeof(Record)));
  if (!comm::root()) return 0;
  const std::size_t n = sim.global_count();
  positions_.assign(3 * n, 0);
  scalar_.assign(n, 0);
  for (const auto& bytes : gathered)
    for (std::size_t at = 0; at + sizeof(Record) <= bytes.size(); at += sizeof(Record)) {
      Record r;
      std::memcpy(&r, bytes.data() + at, sizeof r);
      const auto i = static_cast<std::size_t>(r.id);
      positions_[3 * i] = r.x, positions_[3 * i + 1] = r.y, positions_[3 * i + 2] = r.z;
      scalar_[i] = r.value;
    }
  return n;
}

const std::vector<unsigned char>& ParticleImages::render(Simulation& sim) {
  if (draw_surface_) return render_surface(sim);
  const bool ranks = sim.particles().distributed();
  const std::size_t n = ranks ? collect_on_root(sim) : collect(sim);
  if (ranks && !comm::root()) {
    rgb_.clear();
    return rgb_;
  }
  double lo = min_, hi = max_;
  if (lo == hi) {  // this frame's range
    lo = INFINITY, hi = -INFINITY;
    for (double v : scalar_)
      if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    if (!(lo < hi)) {  // one value (or none): a band around it
      const double centre = std::isfinite(lo) ? lo : 0, half = 0.5 * std::max(std::fabs(centre), 1e-12);
      lo = centre - half, hi = centre + half;
    }
  }
  std::vector<real> x(n), y(n), z(n);
  for (std::size_t i = 0; i < n; ++i) x[i] = positions_[3 * i], y[i] = positions_[3 * i + 1], z[i] = positions_[3 * i + 2];
  std::vector<SolidSurface> solids;
  if (draw_solids_)
    for (const SolidBody* s : sim.solid_bodies()) solids.push_back({&s->surface(), s->fluid_inside()});
  renderer_->render(sim.domain(), x.data(), y.data(), z.data(), scalar_.data(), n, lo, hi,
                    fmt::format("t = {:.3f} s", sim.time()), rgb_, solids);
  return rgb_;
}

// The water's surface with dump/surface's defaults (anisotropic kernels, voxels of half a
// spacing, the walls closed), drawn with the solids.
const std::vector<unsigned char>& ParticleImages::render_surface(Simulation& sim) {
  const SurfaceSettings settings = scene_surface_settings(sim, 0.5, 2.0);  // collective
  DumpFields no_fields(Names{});
  const SurfaceMesh water = scene_surface(sim, no_fields, settings);     // on rank 0
  if (sim.particles().distributed() && !comm::root()) {
    rgb_.clear();
    return rgb_;
  }
  std::vector<SolidSurface> surfaces;
  if (draw_solids_)
    for (const SolidBody* s : sim.solid_bodies()) surfaces.push_back({&s->surface(), s->fluid_inside()});
  surfaces.push_back({&water.mesh, false, true, &water.normals});
  const real none = 0;
  const double no_value = 0;
  renderer_->render(sim.domain(), &none, &none, &none, &no_value, 0, 0, 1, fmt::format("t = {:.3f} s", sim.time()), rgb_,
                    surfaces);
  return rgb_;
}

}  // namespace pbf

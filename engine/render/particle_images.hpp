#pragma once
// Pictures of the particles for dump/image and dump/movie: the parameters both styles take
// (colour field and scale, camera, size, whether to draw the solids, spheres or the water's
// surface) and the rendering of the current state.
#include <string>
#include <vector>

#include "engine/output/dump_fields.hpp"
#include "engine/render/image_renderer.hpp"
#include "engine/registry/params.hpp"

namespace pbf {

class Simulation;

class ParticleImages {
 public:
  static std::vector<ParamSpec> params();
  explicit ParticleImages(const Params& p);

  // In the fix's init: checks the colour field, picks the sphere radius if not given.
  void init(Simulation& sim);
  // Renders the current state; the returned buffer is width * height * 3 bytes, RGB. In a
  // distributed run every rank calls it (the particles are gathered on rank 0) and only rank
  // 0's buffer holds the picture (the others' are empty).
  const std::vector<unsigned char>& render(Simulation& sim);
  int width() const { return spec_.width; }
  int height() const { return spec_.height; }

 private:
  static double colour_value(const real* values, int components);
  std::size_t collect(Simulation& sim);
  std::size_t collect_on_root(Simulation& sim);
  const std::vector<unsigned char>& render_surface(Simulation& sim);
  ImageSpec spec_;
  std::optional<ImageRenderer> renderer_;
  DumpFields color_;
  double min_, max_;
  bool draw_solids_ = true;
  bool draw_surface_ = false;  // draw = "surface": the water's surface instead of spheres
  std::vector<real> values_, positions_;
  std::vector<double> scalar_;
  std::vector<unsigned char> rgb_;
};

}  // namespace pbf

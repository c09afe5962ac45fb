#pragma once
// A software renderer that draws particles as shaded spheres into an RGB image, with the
// domain box, a colour bar, a caption, an axis triad and a scale bar, for image dumps. No
// GPU, no display.
//
// The camera is a perspective one with a 30 degree vertical field of view, looking along
// `direction` at `center`, from the distance at which the domain's bounding sphere fits the
// scene area (the image less the colour bar strip) with a small margin; `zoom` narrows the
// field of view (a lens zoom: the camera does not move, so it stays outside the box).
//
// Rendering is parallel (OpenMP) and deterministic: the same input gives the same bytes at
// any thread count. Each pixel shows the particle whose sphere surface is nearest there, the
// smaller particle index on a tie. Box edges are depth-tested against the particles' sphere
// surfaces, so edges behind the fluid are hidden and edges in front of it drawn.
//
// Solids' surfaces share the z-buffer: opaque, flat grey triangles lit like the spheres. A
// container shows only the triangles that face away from the camera (its floor and far walls,
// seen from inside), so the fluid in it stays in view; an obstacle shows the ones facing it.
// On a tie between a sphere and a triangle the sphere wins; between triangles, the first.
#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/core/domain.hpp"
#include "engine/geometry/triangle_mesh.hpp"
#include "engine/render/colormap.hpp"
#include "engine/render/image_text.hpp"
#include "engine/core/real.hpp"

namespace pbf {

struct ImageSpec {
  int width = 800, height = 600;  // pixels
  // View direction, from the camera toward the look-at point (need not be unit). The default,
  // with up = +z, shows +x to the right, +y going away and +z up, seen a little from above.
  std::array<double, 3> direction{1, 2, -1};
  std::array<double, 3> up{0, 0, 1};
  std::optional<std::array<double, 3>> center;  // look-at point; default the domain centre
  std::optional<std::array<double, 3>> eye;     // camera position; default: back along direction, the domain in view
  double zoom = 1.0;                 // 1: the whole domain box fits in the image with a small margin; 2: twice as large
  double radius = 0;                 // sphere radius in metres drawn per particle; must be set (> 0)
  std::string colormap = "viridis";  // Colormap::names()
  std::string label;                 // colour bar title, e.g. "speed (m/s)"
  bool draw_box = true;              // draw the domain box edges as lines
  bool colorbar = true;
  bool axes = true;       // the axis triad at the bottom left
  bool scale_bar = true;  // the scale bar at the bottom right, where one fits
  std::array<unsigned char, 3> background{255, 255, 255};
};

// The sphere shading, Blinn-Phong in camera coordinates (x right, y up, z toward the
// viewer): colour = base * (ambient + diffuse * max(0, n.L)) + 255 * specular * max(0, n.H)^32,
// with the light L slightly above and left of the camera and H the half vector of L and the
// view direction (0, 0, 1). Public so that tests can predict a pixel.
struct SphereShading {
  static constexpr float light[3] = {-0.3f, 0.4f, 0.866025f};  // unit length
  static constexpr float ambient = 0.3f, diffuse = 0.7f, specular = 0.25f;
  static constexpr int shininess = 32;  // a power of two: computed by squaring
};

// A solid's surface to draw: triangles in world coordinates, counter-clockwise seen from
// outside; `container`: the fluid is inside, so the camera is shown the inside. With `water`,
// the water's surface (dump/surface's mesh): its front faces, shaded as water (WaterShading)
// with the average of their corners' `normals` (per vertex, unit, outward) where given.
struct SolidSurface {
  const TriangleMesh* mesh = nullptr;
  bool container = false;
  bool water = false;
  const std::vector<std::array<float, 3>>* normals = nullptr;
};

// Water: a body colour lit like the solids, mixed with the sky's colour by Schlick's Fresnel
// term for water (F0 = 0.02: the surface reflects more the more grazing the view), plus a
// Blinn-Phong highlight from the spheres' light:
//   colour = (1 - F) body (ambient + diffuse max(0, n.L)) + F sky + 255 specular max(0, n.H)^64,
//   F = F0 + (1 - F0) (1 - n.V)^5, V toward the camera.
struct WaterShading {
  static constexpr float body[3] = {40, 110, 165}, sky[3] = {215, 232, 245};
  static constexpr float f0 = 0.02f, specular = 0.6f;
};

// The solids' shading: a neutral grey, Lambert-lit by the spheres' light (SphereShading) with
// the normal of the side the camera sees: grey * (ambient + diffuse * max(0, n.L)).
struct SolidShading {
  static constexpr float grey = 190.0f;
};

// A scale bar: `metres` long (1, 2 or 5 x 10^k m), `pixels` long in the picture at the depth
// of the camera's look-at point (a perspective picture has one scale per depth), labelled
// e.g. "0.1 m".
struct ScaleBar {
  double metres = 0, pixels = 0;
  std::string label;
};

// The longest round length (1, 2 or 5 x 10^k m) at most max_pixels long at pixels_per_metre;
// none where either is not finite and positive.
std::optional<ScaleBar> round_scale_bar(double pixels_per_metre, double max_pixels);

class ImageRenderer {
 public:
  // Validates the spec (width and height 16..8192, zoom > 0, radius > 0, direction non-zero
  // and not parallel to up, a known colour map) and loads the font
  // /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf (Debian package fonts-dejavu-core);
  // throws pbf::Error naming the parameter or the file.
  explicit ImageRenderer(const ImageSpec& spec);

  // Renders into rgb (resized to width*height*3, row-major, top row first). value[i] is the
  // colour field of particle i, mapped linearly from [vmin, vmax] (vmin < vmax, both finite,
  // else pbf::Error) to the colour map; values outside clamp, NaN draws grey. caption is drawn
  // at the top left (e.g. "t = 1.250 s"). Labels are UTF-8. `solids` are drawn with the
  // particles; a triangle naming a vertex its mesh lacks is a pbf::Error.
  void render(const Domain& domain, const real* x, const real* y, const real* z, const double* value, std::size_t n,
              double vmin, double vmax, const std::string& caption, std::vector<unsigned char>& rgb,
              const std::vector<SolidSurface>& solids = {}) const;

  // The scale bar that render() draws for `domain`: none when the spec turns it off or it
  // does not fit beside the axis triad (a small image).
  std::optional<ScaleBar> scale_bar(const Domain& domain) const;

  int width() const { return spec_.width; }
  int height() const { return spec_.height; }
  const ImageSpec& spec() const { return spec_; }

 private:
  ImageSpec spec_;
  Colormap colormap_;
  std::shared_ptr<const TextRenderer> font_;  // shared: copies of a renderer share the font
};

// Writes an RGB image (width*height*3 bytes, top row first) as PNG via stb_image_write;
// throws pbf::Error naming the path on failure.
void write_png(const std::string& path, int width, int height, const std::vector<unsigned char>& rgb);

}  // namespace pbf

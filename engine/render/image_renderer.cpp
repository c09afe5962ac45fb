#include "engine/render/image_renderer.hpp"

#include <fmt/format.h>
#include <omp.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <limits>
#include <utility>

#include "engine/core/error.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/render/camera.hpp"
#include "engine/render/image_overlay.hpp"
#include "engine/render/image_text.hpp"
#include "engine/render/solid_raster.hpp"
#include "engine/render/tile_bins.hpp"

namespace pbf {

using render::Camera;
using render::cross;
using render::finite;
using render::kTile;
using render::norm;
using render::ScreenPolygon;
using render::TileBins;
using render::TileRange;
using render::unit;
using render::Vec3;

namespace {

// A pixel's owner: a particle's index i, a solid's triangle as n + its index, or none.
constexpr std::uint32_t kNoParticle = std::numeric_limits<std::uint32_t>::max();

// Text and lines are dark on a light background and light on a dark one.
Rgb ink_for(const Rgb& background) {
  const int luminance = (299 * background[0] + 587 * background[1] + 114 * background[2]) / 1000;
  return luminance >= 128 ? Rgb{25, 25, 25} : Rgb{230, 230, 230};
}

}  // namespace


namespace {

// Where the colour bar goes; the scene is centred in the rest of the image. Fixed by the spec
// alone (not by vmin, vmax) so that the camera does not jump between frames.
struct Layout {
  int scene_width;  // the image width less the colour bar strip
  int bar_x, bar_y, bar_w, bar_h;
  int tick_length, margin;
};

Layout make_layout(const ImageSpec& spec, const TextRenderer& font) {
  const int W = spec.width, H = spec.height, fs = font.pixels();
  Layout l{};
  l.margin = fs;
  l.tick_length = std::max(3, fs / 3);
  l.bar_w = std::max(8, fs);
  l.bar_h = H * 3 / 5;
  l.bar_y = (H - l.bar_h) / 2 + fs / 2;  // a little low, leaving room for the title above
  // The widest label "{:.3g}" can make (digits are equally wide in DejaVu Sans).
  const int strip = l.margin + l.bar_w + l.tick_length + fs / 3 + font.width("-8.88e-88") + l.margin / 2;
  l.scene_width = spec.colorbar ? std::max(W / 2, W - strip) : W;
  l.bar_x = l.scene_width + l.margin;
  return l;
}

// A particle as drawn: a disc on the screen, its centre's depth and its colour.
struct Disc {
  float sx, sy, r, depth;
  Rgb colour;
  bool visible;
  // The tiles the disc's bounding square overlaps, if it is drawn.
  std::optional<TileRange> tiles(const TileBins& bins) const {
    if (!visible) return std::nullopt;
    return TileRange(sx - r, sx + r, sy - r, sy + r, bins.tiles_x, bins.tiles_y);
  }
};

// Projects every particle into a disc on the screen, each in its own record (parallel).
void project_particles(const Camera& cam, const Colormap& colormap, double sphere_radius, int scene_width, int height,
                       const real* x, const real* y, const real* z, const double* value, std::size_t n, double vmin,
                       double vmax, std::vector<Disc>& discs) {
  discs.resize(n);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    Disc& d = discs[i];
    const Vec3 c = cam.to_camera({double(x[i]), double(y[i]), double(z[i])});
    d.depth = static_cast<float>(c[2]);
    d.sx = static_cast<float>(cam.screen_x(c));
    d.sy = static_cast<float>(cam.screen_y(c));
    // At least about a pixel wide, so that no particle vanishes however far or small.
    d.r = std::max(0.75f, static_cast<float>(cam.focal * sphere_radius / c[2]));
    d.colour = colormap.at(value[i], vmin, vmax);
    d.visible = c[2] > cam.near + sphere_radius && std::isfinite(d.sx) && std::isfinite(d.sy) && std::isfinite(d.r) &&
                d.sx + d.r >= 0 && d.sx - d.r <= scene_width && d.sy + d.r >= 0 && d.sy - d.r <= height;
  }
}

// Renders one tile, which owns its pixels: a z-buffer pass over its discs (the depth of the
// sphere's front surface at each pixel centre) and then its solid triangles, then shading of
// the nearest per pixel.
void render_tile(int tile, const TileBins& bins, const std::vector<Disc>& discs, float sphere_radius,
                 const TileBins& triangle_bins, const std::vector<ScreenPolygon>& polygons, const Camera& cam,
                 const Rgb& background, int width, std::vector<unsigned char>& rgb, std::vector<float>& depth) {
  const int x0 = tile % bins.tiles_x * kTile, y0 = tile / bins.tiles_x * kTile;
  const int x1 = std::min(bins.area_width, x0 + kTile), y1 = std::min(bins.area_height, y0 + kTile);
  float zbuf[kTile * kTile];
  std::uint32_t owner[kTile * kTile];
  std::fill(std::begin(zbuf), std::end(zbuf), std::numeric_limits<float>::infinity());
  std::fill(std::begin(owner), std::end(owner), kNoParticle);
  for (std::size_t s = bins.start[tile]; s < bins.start[tile + 1]; ++s) {
    const std::uint32_t i = bins.items[s];
    const Disc& d = discs[i];
    const float inv_r2 = 1.0f / (d.r * d.r);
    // The pixels whose centres (p + 0.5) may lie inside the disc, within the tile.
    auto first = [](float lo, int begin, int end) {
      return int(std::clamp(std::ceil(lo - 0.5f), float(begin), float(end)));
    };
    const int row0 = first(d.sy - d.r, y0, y1), row1 = first(d.sy + d.r, y0, y1);
    const int col0 = first(d.sx - d.r, x0, x1), col1 = first(d.sx + d.r, x0, x1);
    for (int py = row0; py < row1; ++py) {
      const float dy = py + 0.5f - d.sy;
      for (int px = col0; px < col1; ++px) {
        const float dx = px + 0.5f - d.sx;
        const float q = (dx * dx + dy * dy) * inv_r2;
        if (q >= 1.0f) continue;
        const float surface = d.depth - sphere_radius * std::sqrt(1.0f - q);
        const int k = (py - y0) * kTile + (px - x0);
        // A tie keeps the smaller index, already there as the list is in ascending order.
        if (surface < zbuf[k]) zbuf[k] = surface, owner[k] = i;
      }
    }
  }
  const auto n = static_cast<std::uint32_t>(discs.size());
  for (std::size_t s = triangle_bins.start[tile]; s < triangle_bins.start[tile + 1]; ++s) {
    const std::uint32_t t = triangle_bins.items[s];
    render::rasterize(polygons[t], x0, y0, x1, y1, zbuf, owner, n + t);
  }
  const float* light = SphereShading::light;
  const float half_norm = std::sqrt(light[0] * light[0] + light[1] * light[1] + (light[2] + 1) * (light[2] + 1));
  const float half[3] = {light[0] / half_norm, light[1] / half_norm, (light[2] + 1) / half_norm};
  for (int py = y0; py < y1; ++py)
    for (int px = x0; px < x1; ++px) {
      const int k = (py - y0) * kTile + (px - x0);
      unsigned char* out = &rgb[(static_cast<std::size_t>(py) * width + px) * 3];
      depth[static_cast<std::size_t>(py) * width + px] = zbuf[k];
      if (owner[k] == kNoParticle) {
        std::copy(background.begin(), background.end(), out);
        continue;
      }
      if (owner[k] >= n) {  // a solid: flat shaded; water per pixel
        const ScreenPolygon& polygon = polygons[owner[k] - n];
        const Rgb colour = polygon.water ? render::water_pixel(polygon, cam, px + 0.5, py + 0.5) : polygon.colour;
        std::copy(colour.begin(), colour.end(), out);
        continue;
      }
      const Disc& d = discs[owner[k]];
      // The sphere's normal here, in camera coordinates with z toward the viewer.
      const float nx = (px + 0.5f - d.sx) / d.r, ny = -(py + 0.5f - d.sy) / d.r;
      const float nz = std::sqrt(std::max(0.0f, 1.0f - nx * nx - ny * ny));
      const float lambert = std::max(0.0f, nx * light[0] + ny * light[1] + nz * light[2]);
      float highlight = std::max(0.0f, nx * half[0] + ny * half[1] + nz * half[2]);
      for (int power = 1; power < SphereShading::shininess; power *= 2) highlight *= highlight;
      const float lit = SphereShading::ambient + SphereShading::diffuse * lambert;
      const float shine = 255.0f * SphereShading::specular * highlight;
      for (int c = 0; c < 3; ++c)
        out[c] = static_cast<unsigned char>(std::min(255.0f, d.colour[c] * lit + shine + 0.5f));
    }
}

// Draws the domain box's edges as antialiased lines over the rendered particles, hidden where a
// particle's surface is nearer than the edge (depth holds the particles' depth per pixel).
void draw_box(const Camera& cam, const Domain& domain, const std::vector<float>& depth, int scene_width,
              std::vector<unsigned char>& rgb, int W, int H, const Rgb& colour) {
  const double half_width = 0.5 * std::max(1.0, H / 600.0);
  auto corner = [&](int k) {
    return Vec3{domain.lo[0] + (k & 1) * domain.extent(0), domain.lo[1] + (k >> 1 & 1) * domain.extent(1),
                domain.lo[2] + (k >> 2 & 1) * domain.extent(2)};
  };
  for (int a = 0; a < 8; ++a)
    for (int bit = 1; bit < 8; bit <<= 1) {
      if (a & bit) continue;  // each edge once: from the corner without the bit to the one with it
      Vec3 p = cam.to_camera(corner(a)), q = cam.to_camera(corner(a | bit));
      if (p[2] < cam.near && q[2] < cam.near) continue;
      if (p[2] < cam.near || q[2] < cam.near) {  // clip off the part behind the camera
        Vec3& behind = p[2] < cam.near ? p : q;
        const Vec3 front = p[2] < cam.near ? q : p;
        const double s = (cam.near - front[2]) / (behind[2] - front[2]);
        for (int c = 0; c < 3; ++c) behind[c] = front[c] + s * (behind[c] - front[c]);
      }
      const double x0 = cam.screen_x(p), y0 = cam.screen_y(p), x1 = cam.screen_x(q), y1 = cam.screen_y(q);
      const double dx = x1 - x0, dy = y1 - y0, length = std::hypot(dx, dy);
      if (!(length > 1e-9) || !std::isfinite(length)) continue;
      // Step one pixel at a time along the major axis, covering the pixels across the line.
      const bool steep = std::fabs(dy) > std::fabs(dx);
      const double m0 = steep ? y0 : x0, m1 = steep ? y1 : x1, n0 = steep ? x0 : y0, n1 = steep ? x1 : y1;
      const double major_size = steep ? H : scene_width, minor_size = steep ? scene_width : H;
      auto pixel = [](double v, double size) { return int(std::clamp(v, -1.0, size)); };
      const int first = pixel(std::ceil(std::min(m0, m1) - 0.5), major_size);
      const int last = pixel(std::floor(std::max(m0, m1) - 0.5), major_size - 1);
      for (int m = std::max(first, 0); m <= last; ++m) {
        const double s = (m + 0.5 - m0) / (m1 - m0);  // where on the edge, on the screen
        const double across = n0 + s * (n1 - n0);
        const double edge_depth = 1 / ((1 - s) / p[2] + s / q[2]);  // 1/depth is linear on the screen
        const int k1 = pixel(std::ceil(across + half_width + 1), minor_size - 1);
        for (int k = std::max(0, pixel(std::floor(across - half_width - 1), minor_size)); k <= k1; ++k) {
          const int px = steep ? k : m, py = steep ? m : k;
          const double distance = std::fabs((px + 0.5 - x0) * dy - (py + 0.5 - y0) * dx) / length;
          const double coverage = std::clamp(half_width + 0.5 - distance, 0.0, 1.0);
          if (coverage > 0 && edge_depth <= depth[static_cast<std::size_t>(py) * W + px])
            blend(rgb, W, H, px, py, colour, static_cast<float>(coverage));
        }
      }
    }
}

void draw_colorbar(const Layout& l, const Colormap& colormap, const TextRenderer& font, double vmin, double vmax,
                   const std::string& label, std::vector<unsigned char>& rgb, int W, int H, const Rgb& ink) {
  for (int row = 0; row < l.bar_h; ++row) {  // top row is vmax
    const Rgb c = colormap(1.0 - static_cast<double>(row) / std::max(1, l.bar_h - 1));
    for (int col = 0; col < l.bar_w; ++col) blend(rgb, W, H, l.bar_x + col, l.bar_y + row, c, 1.0f);
  }
  for (int k = -1; k <= l.bar_w; ++k)  // a thin frame
    blend(rgb, W, H, l.bar_x + k, l.bar_y - 1, ink, 1.0f), blend(rgb, W, H, l.bar_x + k, l.bar_y + l.bar_h, ink, 1.0f);
  for (int row = 0; row < l.bar_h; ++row)
    blend(rgb, W, H, l.bar_x - 1, l.bar_y + row, ink, 1.0f),
        blend(rgb, W, H, l.bar_x + l.bar_w, l.bar_y + row, ink, 1.0f);
  for (double value : colorbar_ticks(vmin, vmax)) {
    const int y = l.bar_y + static_cast<int>(std::lround((vmax - value) / (vmax - vmin) * (l.bar_h - 1)));
    for (int k = 0; k < l.tick_length; ++k) blend(rgb, W, H, l.bar_x + l.bar_w + k, y, ink, 1.0f);
    const std::string text = fmt::format("{:.3g}", value == 0 ? 0.0 : value);  // no "-0"
    font.draw(rgb, W, H, l.bar_x + l.bar_w + l.tick_length + font.pixels() / 3, y + font.pixels() * 3 / 8, text, ink);
  }
  if (!label.empty()) {  // centred over the bar, kept inside the image
    const int text_width = font.width(label);
    const int x = std::max(0, std::min(l.bar_x + l.bar_w / 2 - text_width / 2, W - text_width - 2));
    font.draw(rgb, W, H, x, l.bar_y - font.pixels() * 3 / 4, label, ink);
  }
}

}  // namespace

// ---------------------------------------------------------------------------------------------

ImageRenderer::ImageRenderer(const ImageSpec& spec) : spec_(spec), colormap_(spec.colormap) {
  if (spec.width < 16 || spec.width > 8192)
    throw Error(fmt::format("image: width must be 16..8192 pixels, got {}", spec.width));
  if (spec.height < 16 || spec.height > 8192)
    throw Error(fmt::format("image: height must be 16..8192 pixels, got {}", spec.height));
  if (!(spec.zoom > 0) || !std::isfinite(spec.zoom))
    throw Error(fmt::format("image: zoom must be > 0, got {}", spec.zoom));
  if (!(spec.radius > 0) || !std::isfinite(spec.radius))
    throw Error(fmt::format("image: radius (of the particle spheres, m) must be > 0, got {}", spec.radius));
  if (!finite(spec.direction) || spec.direction == Vec3{0, 0, 0})
    throw Error("image: direction must be a finite non-zero vector");
  if (!finite(spec.up) || spec.up == Vec3{0, 0, 0}) throw Error("image: up must be a finite non-zero vector");
  // Parallel (the sine of the angle below 1e-3) leaves the camera's roll undefined.
  // (With a camera position, the direction is from it to the centre, checked when drawing.)
  if (!spec.eye && norm(cross(unit(spec.direction), unit(spec.up))) <= 1e-3)
    throw Error("image: direction must not be parallel to up");
  if (spec.center && !finite(*spec.center)) throw Error("image: center must be finite");
  if (spec.eye && !finite(*spec.eye)) throw Error("image: the camera position must be finite");
  font_ = std::make_shared<const TextRenderer>(std::clamp(spec.height / 36, 10, 96));
}

void ImageRenderer::render(const Domain& domain, const real* x, const real* y, const real* z, const double* value,
                           std::size_t n, double vmin, double vmax, const std::string& caption,
                           std::vector<unsigned char>& rgb, const std::vector<SolidSurface>& solids) const {
  if (!(std::isfinite(vmin) && std::isfinite(vmax) && vmin < vmax && std::isfinite(vmax - vmin)))
    throw Error(fmt::format("image: the colour range needs finite vmin < vmax, got {} and {}", vmin, vmax));
  std::size_t triangles = 0;
  for (std::size_t s = 0; s < solids.size(); ++s) {
    const TriangleMesh& mesh = *solids[s].mesh;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
      for (std::uint32_t v : mesh.triangles[t])
        if (v >= mesh.vertices.size())
          throw Error(fmt::format("image: triangle {} of solid surface {} names vertex {}, but the surface has {}", t,
                                  s + 1, v, mesh.vertices.size()));
    triangles += mesh.triangles.size();
  }
  if (n + triangles >= kNoParticle)
    throw Error(
        fmt::format("image: cannot render {} particles and {} triangles (at most 2^32 - 2 together)", n, triangles));
  const int W = spec_.width, H = spec_.height;
  const Layout layout = make_layout(spec_, *font_);
  const Camera cam(spec_, domain, layout.scene_width);

  // 1. Particles to discs and solids' triangles to polygons on the screen, binned into tiles.
  std::vector<Disc> discs;
  project_particles(cam, colormap_, spec_.radius, layout.scene_width, H, x, y, z, value, n, vmin, vmax, discs);
  TileBins bins(layout.scene_width, H);
  bins.bin(n, [&](std::size_t i) { return discs[i].tiles(bins); });
  const std::vector<ScreenPolygon> polygons = render::project_solids(cam, solids, layout.scene_width, H);
  TileBins triangle_bins(layout.scene_width, H);
  triangle_bins.bin(polygons.size(), [&](std::size_t t) { return polygons[t].tiles(triangle_bins); });

  // 2. The scene area, tile by tile in parallel; then the colour bar strip's background.
  rgb.resize(static_cast<std::size_t>(W) * H * 3);
  std::vector<float> depth(static_cast<std::size_t>(W) * H, std::numeric_limits<float>::infinity());
  const int tile_count = bins.count();
#pragma omp parallel for schedule(dynamic, 1)
  for (int tile = 0; tile < tile_count; ++tile)
    render_tile(tile, bins, discs, static_cast<float>(spec_.radius), triangle_bins, polygons, cam, spec_.background, W,
                rgb, depth);
  for (int py = 0; py < H; ++py)
    for (int px = layout.scene_width; px < W; ++px)
      std::copy(spec_.background.begin(), spec_.background.end(), &rgb[(static_cast<std::size_t>(py) * W + px) * 3]);

  // 3. Overlays, serial and in a fixed order: box edges, colour bar, caption, triad, scale bar.
  const Rgb ink = ink_for(spec_.background);
  if (spec_.draw_box) draw_box(cam, domain, depth, layout.scene_width, rgb, W, H, ink);
  if (spec_.colorbar) draw_colorbar(layout, colormap_, *font_, vmin, vmax, spec_.label, rgb, W, H, ink);
  if (!caption.empty()) font_->draw(rgb, W, H, font_->pixels() * 2 / 3, font_->pixels() / 2 + font_->ascent(), caption, ink);
  const render::GuideLayout guides(*font_, layout.scene_width, H);
  if (spec_.axes && guides.triad_fits) render::draw_axis_triad(cam, guides, *font_, rgb, W, spec_.background);
  const auto bar = spec_.scale_bar ? render::fit_scale_bar(cam, guides, *font_, spec_.axes) : std::nullopt;
  if (bar) render::draw_scale_bar(*bar, guides, *font_, spec_.axes, rgb, W, ink, spec_.background);
}

std::optional<ScaleBar> ImageRenderer::scale_bar(const Domain& domain) const {
  if (!spec_.scale_bar) return std::nullopt;
  const Layout layout = make_layout(spec_, *font_);
  const Camera cam(spec_, domain, layout.scene_width);
  return render::fit_scale_bar(cam, render::GuideLayout(*font_, layout.scene_width, spec_.height), *font_, spec_.axes);
}

void write_png(const std::string& path, int width, int height, const std::vector<unsigned char>& rgb) {
  if (width <= 0 || height <= 0 || rgb.size() != static_cast<std::size_t>(width) * height * 3)
    throw Error(fmt::format("image: cannot write {}: the data are not a {}x{} RGB image", path, width, height));
  // Encoded in memory, then written whole: stb's own file writer does not check its writes,
  // and a full disk would leave a cut-off picture under the final name.
  std::string png;
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &png, width, height, 3, rgb.data(), width * 3))
    throw Error(fmt::format("image: cannot encode the PNG file {}", path));
  AtomicFile file(path);
  file.write(png);
  file.commit();
}

}  // namespace pbf

#pragma once
// The solids' triangles in the image renderer: each projected, culled by the side it shows
// the camera, clipped to the view and flat shaded once (in parallel, one record each), then
// drawn tile by tile into the same z-buffer as the particles' spheres. Internal to
// engine/render.
//
// Clipping is in camera space, against the near plane and the four sides of the view widened
// by a guard band of a few pixels, so a triangle behind the camera or far larger than the
// image leaves a convex polygon whose corners lie on or just beyond the image: the pixel tests
// stay exact whatever the scale. Pixels are tested at their centres against each edge, the edge
// always evaluated from its lower endpoint: two triangles sharing an edge compute the same
// number with opposite signs and both take a pixel centre that lies exactly on it, so a
// closed surface shows no cracks (the z-buffer's tie rule picks one, the same at any thread
// count).
#include <cstdint>
#include <optional>
#include <vector>

#include "engine/render/camera.hpp"
#include "engine/render/colormap.hpp"
#include "engine/render/image_renderer.hpp"
#include "engine/render/tile_bins.hpp"

namespace pbf::render {

// A triangle as drawn: the convex polygon left of it in the view, on the screen.
struct ScreenPolygon {
  static constexpr int kMaxCorners = 8;          // a triangle clipped by five planes
  int corners = 0;                               // 0: not drawn (culled, outside the view, degenerate)
  float x[kMaxCorners], y[kMaxCorners];          // pixel coordinates, counter-clockwise (positive area)
  double a = 0, b = 0, c = 0;                    // 1 / depth = a x + b y + c over the screen (perspective-correct)
  float x_lo = 0, x_hi = 0, y_lo = 0, y_hi = 0;  // bounding box
  Rgb colour{};
  // Water is shaded per pixel: its corners' normals (camera axes, toward the side seen),
  // interpolated at the point seen, where the triangle's corners are (camera space).
  bool water = false;
  float corner[3][3] = {}, normal[3][3] = {};

  std::optional<TileRange> tiles(const TileBins& bins) const {
    if (corners == 0) return std::nullopt;
    return TileRange(x_lo, x_hi, y_lo, y_hi, bins.tiles_x, bins.tiles_y);
  }
};

// The triangles of every surface in order (solid 0's, then solid 1's, ...), as drawn by the
// camera over a scene area of width x height pixels. Containers show their back faces (the
// inside of the far walls and the floor), obstacles their front faces. The surfaces' vertex
// indices must be valid (ImageRenderer::render checks them).
std::vector<ScreenPolygon> project_solids(const Camera& cam, const std::vector<SolidSurface>& solids, int width,
                                          int height);

// Draws a polygon into a tile's z-buffer (kTile x kTile, the tile's top left at x0, y0),
// within the pixels [x0, x1) x [y0, y1): where a pixel centre is inside the polygon and the
// polygon is nearer than zbuf (strictly: a tie keeps what is there), zbuf takes its depth
// and owner takes `id`.
void rasterize(const ScreenPolygon& p, int x0, int y0, int x1, int y1, float* zbuf, std::uint32_t* owner,
               std::uint32_t id);

// A water polygon's colour at the pixel centre (qx, qy): WaterShading's Fresnel, diffuse and
// highlight with the normal interpolated from its corners' (Phong shading), so the facets of
// the mesh do not show.
Rgb water_pixel(const ScreenPolygon& p, const Camera& cam, double qx, double qy);

}  // namespace pbf::render

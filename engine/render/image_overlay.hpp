#pragma once
// The picture's guides, drawn over the scene area after everything else: an axis triad at its
// bottom left and a scale bar at its bottom right. Internal to engine/render.
//
// The triad shows the world axes x, y, z in red, green and blue, each a line from a common
// origin labelled at its tip, as the camera sees directions at its look-at point: there the
// perspective projection of a short step along an axis is the step's component along the
// camera's right and up axes, so the triad is that component, the same for any distance. The
// axis pointing most toward the viewer is drawn last, over the others.
//
// The scale bar is the longest round length (ScaleBar) at most a quarter of the scene area's
// width at the look-at point's depth, where nearer things look larger and farther ones
// smaller. Either guide is left out where it does not fit (a small picture).
#include <optional>
#include <vector>

#include "engine/render/camera.hpp"
#include "engine/render/image_renderer.hpp"
#include "engine/render/image_text.hpp"

namespace pbf::render {

// The colours of the axes x, y and z.
inline constexpr Rgb kAxisColours[3] = {Rgb{214, 39, 40}, Rgb{44, 160, 44}, Rgb{31, 119, 180}};

// Where the guides go, from the font size alone (so that they stay put from frame to frame).
struct GuideLayout {
  GuideLayout(const TextRenderer& font, int scene_width, int height);
  int scene_width, height;
  int margin;       // from the scene area's edges
  double arm;       // the triad's axis length in pixels
  double origin_x, origin_y;
  int triad_right;  // the column right of the triad and its labels
  bool triad_fits;  // inside the scene area, below the caption
};

// Each stroke of the guides has a rim of the background colour, so that it reads over particles.
void draw_axis_triad(const Camera& cam, const GuideLayout& l, const TextRenderer& font, std::vector<unsigned char>& rgb,
                     int width, const Rgb& background);

// The scale bar that fits between the triad (or the left margin without one) and the right
// margin, at the camera's pixels per metre at its look-at point; none where none fits.
std::optional<ScaleBar> fit_scale_bar(const Camera& cam, const GuideLayout& l, const TextRenderer& font, bool axes);

// Draws the bar right-aligned at the bottom of the scene area, `lround(bar.pixels)` columns
// long with a tick up at each end, its label over it.
void draw_scale_bar(const ScaleBar& bar, const GuideLayout& l, const TextRenderer& font, bool axes,
                    std::vector<unsigned char>& rgb, int width, const Rgb& ink, const Rgb& background);

}  // namespace pbf::render

#include "engine/render/image_overlay.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace pbf {

std::optional<ScaleBar> round_scale_bar(double pixels_per_metre, double max_pixels) {
  if (!(pixels_per_metre > 0 && std::isfinite(pixels_per_metre) && max_pixels > 0 && std::isfinite(max_pixels)))
    return std::nullopt;
  const double most = max_pixels / pixels_per_metre;  // metres
  if (!(most > 0 && std::isfinite(most))) return std::nullopt;
  double power = std::pow(10.0, std::floor(std::log10(most)));
  if (most / power < 1) power /= 10;  // log10 rounded up across a power of ten
  const double mantissa = most / power;
  ScaleBar bar;
  bar.metres = (mantissa >= 5 ? 5 : mantissa >= 2 ? 2 : 1) * power;
  bar.pixels = bar.metres * pixels_per_metre;
  bar.label = fmt::format("{:g} m", bar.metres);
  return bar;
}

namespace render {

namespace {

// An antialiased line segment, half_width thick on either side, with round ends.
void draw_segment(double x0, double y0, double x1, double y1, double half_width, const Rgb& colour,
                  std::vector<unsigned char>& rgb, int width, int height) {
  const double dx = x1 - x0, dy = y1 - y0, length2 = dx * dx + dy * dy, reach = half_width + 1;
  const int c0 = std::max(0, int(std::floor(std::min(x0, x1) - reach)));
  const int c1 = std::min(width - 1, int(std::ceil(std::max(x0, x1) + reach)));
  const int r0 = std::max(0, int(std::floor(std::min(y0, y1) - reach)));
  const int r1 = std::min(height - 1, int(std::ceil(std::max(y0, y1) + reach)));
  for (int py = r0; py <= r1; ++py)
    for (int px = c0; px <= c1; ++px) {
      const double qx = px + 0.5 - x0, qy = py + 0.5 - y0;
      const double s = length2 > 0 ? std::clamp((qx * dx + qy * dy) / length2, 0.0, 1.0) : 0.0;
      const double coverage = std::clamp(half_width + 0.5 - std::hypot(qx - s * dx, qy - s * dy), 0.0, 1.0);
      if (coverage > 0) blend(rgb, width, height, px, py, colour, static_cast<float>(coverage));
    }
}

void fill(std::vector<unsigned char>& rgb, int width, int height, int x0, int x1, int y0, int y1, const Rgb& colour) {
  for (int py = y0; py < y1; ++py)
    for (int px = x0; px < x1; ++px) blend(rgb, width, height, px, py, colour, 1.0f);
}

// The guides lie over the scene: a rim of the background colour around each stroke keeps
// them readable over particles of any colour.
int halo(const TextRenderer& font) { return std::max(1, font.pixels() / 12); }

void draw_text_with_halo(const TextRenderer& font, std::vector<unsigned char>& rgb, int width, int height, int x, int y,
                         const std::string& text, const Rgb& colour, const Rgb& background) {
  const int r = halo(font);
  for (int dy = -r; dy <= r; dy += r)
    for (int dx = -r; dx <= r; dx += r)
      if (dx || dy) font.draw(rgb, width, height, x + dx, y + dy, text, background);
  font.draw(rgb, width, height, x, y, text, colour);
}

}  // namespace

GuideLayout::GuideLayout(const TextRenderer& font, int scene_width_px, int height_px)
    : scene_width(scene_width_px), height(height_px) {
  const int fs = font.pixels();
  margin = fs * 2 / 3;
  arm = 2.5 * fs;
  const double reach = arm + 1.2 * fs;  // the labels sit beyond the tips
  // On a pixel centre, so that an axis along a row or column is sharp.
  origin_x = std::floor(margin + reach) + 0.5;
  origin_y = std::floor(height - margin - reach) + 0.5;
  triad_right = static_cast<int>(std::ceil(origin_x + reach));
  triad_fits = triad_right <= scene_width && origin_y - reach >= 2 * fs;  // clear of the caption
}

void draw_axis_triad(const Camera& cam, const GuideLayout& l, const TextRenderer& font, std::vector<unsigned char>& rgb,
                     int width, const Rgb& background) {
  const int fs = font.pixels();
  const double half_width = std::max(1.0, fs / 8.0);
  std::array<int, 3> order{0, 1, 2};  // the axis pointing farthest away first
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return cam.forward[a] > cam.forward[b]; });
  static constexpr const char* kNames[3] = {"x", "y", "z"};
  for (int k : order) {
    const double dx = cam.right[k], dy = -cam.up[k];  // rows grow downward
    const double tip_x = l.origin_x + l.arm * dx, tip_y = l.origin_y + l.arm * dy;
    draw_segment(l.origin_x, l.origin_y, tip_x, tip_y, half_width + halo(font), background, rgb, width, l.height);
    draw_segment(l.origin_x, l.origin_y, tip_x, tip_y, half_width, kAxisColours[k], rgb, width, l.height);
    const double at = l.arm + 0.7 * fs;
    const int label_x = static_cast<int>(std::lround(l.origin_x + at * dx)) - font.width(kNames[k]) / 2;
    const int baseline = static_cast<int>(std::lround(l.origin_y + at * dy)) + fs * 3 / 8;
    draw_text_with_halo(font, rgb, width, l.height, label_x, baseline, kNames[k], kAxisColours[k], background);
  }
}

namespace {
// The columns the scale bar and its label may take.
int bar_left(const GuideLayout& l, bool axes) { return axes && l.triad_fits ? l.triad_right + l.margin : l.margin; }
int bar_right(const GuideLayout& l) { return l.scene_width - l.margin; }
}  // namespace

std::optional<ScaleBar> fit_scale_bar(const Camera& cam, const GuideLayout& l, const TextRenderer& font, bool axes) {
  const int fs = font.pixels(), room = bar_right(l) - bar_left(l, axes);
  if (room < fs || l.height < 5 * fs) return std::nullopt;  // no room beside the triad, or under the caption
  auto bar = round_scale_bar(cam.focal / cam.focus, std::min(0.25 * l.scene_width, double(room)));
  if (!bar || bar->pixels < fs || font.width(bar->label) > room) return std::nullopt;
  return bar;
}

void draw_scale_bar(const ScaleBar& bar, const GuideLayout& l, const TextRenderer& font, bool axes,
                    std::vector<unsigned char>& rgb, int width, const Rgb& ink, const Rgb& background) {
  const int fs = font.pixels(), thickness = std::max(2, fs / 6), bottom = l.height - l.margin, r = halo(font);
  const int x1 = bar_right(l), x0 = x1 - static_cast<int>(std::lround(bar.pixels));
  const int tick_top = bottom - thickness - fs / 3;
  // The bar and the ticks at its ends, over their halo.
  fill(rgb, width, l.height, x0 - r, x1 + r, bottom - thickness - r, bottom + r, background);
  fill(rgb, width, l.height, x0 - r, x0 + thickness + r, tick_top - r, bottom, background);
  fill(rgb, width, l.height, x1 - thickness - r, x1 + r, tick_top - r, bottom, background);
  fill(rgb, width, l.height, x0, x1, bottom - thickness, bottom, ink);
  fill(rgb, width, l.height, x0, x0 + thickness, tick_top, bottom, ink);
  fill(rgb, width, l.height, x1 - thickness, x1, tick_top, bottom, ink);
  const int text_width = font.width(bar.label);  // centred over the bar, kept clear of the triad
  const int x = std::clamp((x0 + x1 - text_width) / 2, bar_left(l, axes), x1 - text_width);
  draw_text_with_halo(font, rgb, width, l.height, x, bottom - thickness - fs / 4, bar.label, ink, background);
}

}  // namespace render

}  // namespace pbf

// The pictures explain themselves: the default camera shows x to the right and z up; the axis
// triad's axes point where the camera sees the world axes, in their colours; the scale bar is
// as long as its label says at the depth of the look-at point; both can be turned off, and
// are left out of a picture too small for them.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <optional>
#include <vector>

#include "engine/render/image_renderer.hpp"

using pbf::Domain;
using pbf::ImageRenderer;
using pbf::ImageSpec;
using pbf::real;

namespace {

const Domain kBox{{0, 0, 0}, {1, 1, 1}};
using Pixel = std::array<int, 3>;

// The default camera with nothing drawn but the particles (and the guides asked for).
ImageSpec bare_spec(int width, int height, bool axes, bool scale_bar) {
  ImageSpec spec;
  spec.width = width, spec.height = height;
  spec.radius = 0.05;
  spec.draw_box = spec.colorbar = false;
  spec.axes = axes, spec.scale_bar = scale_bar;
  return spec;
}

std::vector<unsigned char> render(const ImageSpec& spec, const std::vector<std::array<real, 3>>& particles = {}) {
  std::vector<real> x, y, z;
  for (const auto& p : particles) x.push_back(p[0]), y.push_back(p[1]), z.push_back(p[2]);
  const std::vector<double> value(particles.size(), 0.5);
  std::vector<unsigned char> rgb;
  ImageRenderer(spec).render(kBox, x.data(), y.data(), z.data(), value.data(), particles.size(), 0.0, 1.0, "", rgb);
  return rgb;
}

Pixel at(const std::vector<unsigned char>& rgb, int width, int x, int y) {
  const unsigned char* p = &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
  return {p[0], p[1], p[2]};
}

// The mean column and row of the pixels that pass `keep`, and how many there are.
struct Centroid {
  double x = 0, y = 0, count = 0;
};
Centroid centroid(const std::vector<unsigned char>& rgb, int width, int height, const std::function<bool(Pixel)>& keep) {
  Centroid c;
  for (int py = 0; py < height; ++py)
    for (int px = 0; px < width; ++px)
      if (keep(at(rgb, width, px, py))) c.x += px + 0.5, c.y += py + 0.5, ++c.count;
  if (c.count > 0) c.x /= c.count, c.y /= c.count;
  return c;
}

bool not_white(Pixel p) { return p != Pixel{255, 255, 255}; }
// The axes' colours where a line covers the pixel fully (antialiased edges are paler).
bool red(Pixel p) { return p[0] > 150 && p[1] < 90 && p[2] < 90; }
bool green(Pixel p) { return p[1] > 120 && p[0] < 90 && p[2] < 90; }
bool blue(Pixel p) { return p[2] > 150 && p[0] < 90 && p[1] < 150; }

}  // namespace

TEST(ImageOverlay, DefaultCameraShowsXToTheRightAndZUp) {
  const int W = 400, H = 300;
  const ImageSpec spec = bare_spec(W, H, false, false);
  auto seen_at = [&](real x, real y, real z) {
    const Centroid c = centroid(render(spec, {{x, y, z}}), W, H, not_white);
    EXPECT_GT(c.count, 0) << x << " " << y << " " << z;
    return c;
  };
  const Centroid left = seen_at(0.2f, 0.5f, 0.5f), right = seen_at(0.8f, 0.5f, 0.5f);
  const Centroid low = seen_at(0.5f, 0.5f, 0.2f), high = seen_at(0.5f, 0.5f, 0.8f);
  EXPECT_GT(right.x, left.x + 50);  // the box spans about 200 columns
  EXPECT_LT(high.y, low.y - 50);    // rows grow downward
}

TEST(ImageOverlay, TriadAxesPointWhereTheCameraSeesThem) {
  const int W = 400, H = 300;
  ImageSpec spec = bare_spec(W, H, true, false);
  // Default camera: x right (a little up), y away and to the left, z straight up. The z axis
  // is a vertical line whose lowest pixels are the origin.
  auto rgb = render(spec);
  const Centroid r = centroid(rgb, W, H, red), g = centroid(rgb, W, H, green), b = centroid(rgb, W, H, blue);
  ASSERT_GT(r.count, 10);
  ASSERT_GT(g.count, 10);
  ASSERT_GT(b.count, 10);
  int origin_row = 0;
  for (int py = 0; py < H; ++py)
    for (int px = 0; px < W / 2; ++px)
      if (blue(at(rgb, W, px, py))) origin_row = py;
  const double origin_col = b.x;
  EXPECT_GT(origin_row, H / 2);     // at the bottom left
  EXPECT_LT(origin_col, W / 4);
  EXPECT_GT(r.x, origin_col + 10);  // the arms are 25 pixels long
  EXPECT_LT(r.y, origin_row + 1);
  EXPECT_LT(g.x, origin_col - 5);
  EXPECT_LT(b.y, origin_row - 10);
  int red_left_of_origin = 0;
  for (int py = 0; py < H; ++py)
    for (int px = 0; px < origin_col - 3; ++px) red_left_of_origin += red(at(rgb, W, px, py));
  EXPECT_EQ(red_left_of_origin, 0);

  // Looking along -x: y to the right, z up, and x, pointing at the viewer, a dot and its
  // label at the origin, drawn over the others.
  spec.direction = {-1, 0, 0};
  rgb = render(spec);
  const Centroid r2 = centroid(rgb, W, H, red), g2 = centroid(rgb, W, H, green), b2 = centroid(rgb, W, H, blue);
  EXPECT_NEAR(g2.y, origin_row, 3);
  EXPECT_GT(g2.x, origin_col + 10);
  EXPECT_NEAR(b2.x, origin_col, 1);
  EXPECT_NEAR(r2.x, origin_col, 3);
  EXPECT_NEAR(r2.y, origin_row, 5);
}

TEST(ImageOverlay, ScaleBarIsItsLabelledLengthAtTheLookAtPointsDepth) {
  const int W = 201, H = 161;
  ImageSpec looking_along_y = bare_spec(W, H, true, true);
  looking_along_y.direction = {0, 1, 0};
  ImageSpec from_nearby = looking_along_y;  // 2 m from the centre: larger than the default view
  from_nearby.eye = std::array<double, 3>{0.5, -1.5, 0.5};
  for (const ImageSpec& spec : {looking_along_y, from_nearby}) {
    // Pixels per metre at the look-at point's depth: two particles there, 0.5 m apart.
    ImageSpec plain = spec;
    plain.axes = plain.scale_bar = false;
    const double ppm = (centroid(render(plain, {{0.75f, 0.5f, 0.5f}}), W, H, not_white).x -
                        centroid(render(plain, {{0.25f, 0.5f, 0.5f}}), W, H, not_white).x) /
                       0.5;
    const std::optional<pbf::ScaleBar> bar = ImageRenderer(spec).scale_bar(kBox);
    ASSERT_TRUE(bar);
    const double mantissa = bar->metres / std::pow(10.0, std::floor(std::log10(bar->metres) + 1e-9));
    EXPECT_TRUE(std::fabs(mantissa - 1) < 1e-9 || std::fabs(mantissa - 2) < 1e-9 || std::fabs(mantissa - 5) < 1e-9)
        << bar->metres;
    EXPECT_EQ(bar->label, fmt::format("{:g} m", bar->metres));
    // The bar in the picture: the longest run of ink along a row.
    const auto rgb = render(spec);
    int longest = 0;
    for (int py = 0; py < H; ++py)
      for (int px = 0, run = 0; px < W; ++px) {
        run = at(rgb, W, px, py) == Pixel{25, 25, 25} ? run + 1 : 0;
        longest = std::max(longest, run);
      }
    EXPECT_NEAR(longest, bar->metres * ppm, 1.0) << bar->label << " at " << ppm << " px/m";
    EXPECT_LE(longest, W / 4 + 1);
    EXPECT_GE(longest, W / 10);
  }
}

TEST(ImageOverlay, RoundScaleBarIsTheLongestRoundLengthThatFits) {
  auto metres = [](double ppm, double max_pixels) { return pbf::round_scale_bar(ppm, max_pixels)->metres; };
  EXPECT_DOUBLE_EQ(metres(83, 50), 0.5);
  EXPECT_DOUBLE_EQ(metres(1000, 250), 0.2);
  EXPECT_DOUBLE_EQ(metres(1000, 100), 0.1);  // exactly the longest allowed
  EXPECT_DOUBLE_EQ(metres(1000, 99.9), 0.05);
  EXPECT_DOUBLE_EQ(metres(1e-3, 400), 2e5);
  EXPECT_EQ(pbf::round_scale_bar(1000, 100)->label, "0.1 m");
  EXPECT_EQ(pbf::round_scale_bar(1000, 60)->label, "0.05 m");
  EXPECT_DOUBLE_EQ(pbf::round_scale_bar(1000, 60)->pixels, 50);
  EXPECT_FALSE(pbf::round_scale_bar(0, 100));
  EXPECT_FALSE(pbf::round_scale_bar(std::nan(""), 100));
  EXPECT_FALSE(pbf::round_scale_bar(INFINITY, 100));
  EXPECT_FALSE(pbf::round_scale_bar(100, 0));
}

TEST(ImageOverlay, GuidesSitInTheirCornersAndTurnOff) {
  const int W = 400, H = 300;
  auto count_in = [&](const std::vector<unsigned char>& rgb, int x0, int x1, int y0, int y1) {
    int n = 0;
    for (int py = y0; py < y1; ++py)
      for (int px = x0; px < x1; ++px) n += not_white(at(rgb, W, px, py));
    return n;
  };
  const auto none = render(bare_spec(W, H, false, false));
  EXPECT_EQ(count_in(none, 0, W, 0, H), 0);
  const auto axes = render(bare_spec(W, H, true, false));
  EXPECT_GT(count_in(axes, 0, W / 3, H / 2, H), 100);
  EXPECT_EQ(count_in(axes, 0, W, 0, H), count_in(axes, 0, W / 3, H / 2, H)) << "triad pixels outside its corner";
  const auto bar = render(bare_spec(W, H, false, true));
  EXPECT_GT(count_in(bar, W / 2, W, H * 3 / 4, H), 50);
  EXPECT_EQ(count_in(bar, 0, W, 0, H), count_in(bar, W / 2, W, H * 3 / 4, H)) << "scale bar pixels outside its corner";

  // Too small for either: left out, not drawn over the scene.
  const ImageSpec tiny = bare_spec(16, 16, true, true);
  const auto rgb = render(tiny);
  EXPECT_EQ(std::count(rgb.begin(), rgb.end(), 255), 16 * 16 * 3);
  EXPECT_FALSE(ImageRenderer(tiny).scale_bar(kBox));
}

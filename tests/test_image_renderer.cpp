// The image renderer draws a particle where the camera looks, in its colour map colour,
// hides farther particles behind nearer ones, gives the same bytes on 1 and 2 threads, and
// rejects bad parameters; write_png writes a PNG file.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <random>

#include "engine/core/error.hpp"
#include "engine/render/image_renderer.hpp"
#include "test_util.hpp"

using pbf::Domain;
using pbf::ImageRenderer;
using pbf::ImageSpec;
using pbf::real;

namespace {

Domain unit_box() { return Domain{{0, 0, 0}, {1, 1, 1}}; }

// A spec looking straight down the y axis at the unit box, no overlays. Odd sizes put the
// image centre, where the domain centre projects, at the centre of pixel (100, 80).
constexpr int kWidth = 201, kHeight = 161;
ImageSpec plain_spec(double radius) {
  ImageSpec spec;
  spec.width = kWidth;
  spec.height = kHeight;
  spec.direction = {0, 1, 0};
  spec.radius = radius;
  spec.draw_box = false;
  spec.colorbar = false;
  spec.axes = false;
  spec.scale_bar = false;
  return spec;
}

const unsigned char* pixel(const std::vector<unsigned char>& rgb, int width, int x, int y) {
  return &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
}

bool is_background(const unsigned char* p, const ImageSpec& spec) {
  return p[0] == spec.background[0] && p[1] == spec.background[1] && p[2] == spec.background[2];
}

}  // namespace

TEST(ImageRenderer, OneParticleIsADiscInTheMapColour) {
  const ImageSpec spec = plain_spec(0.1);
  const ImageRenderer renderer(spec);
  const real x = 0.5, y = 0.5, z = 0.5;
  const double value = 0.25;
  std::vector<unsigned char> rgb;
  renderer.render(unit_box(), &x, &y, &z, &value, 1, 0.0, 1.0, "", rgb);
  ASSERT_EQ(rgb.size(), std::size_t(kWidth) * kHeight * 3);

  // The disc: the pixels that are not background. Its centroid is the image centre (the
  // camera looks at the domain centre), and its area that of a circle of the perspective
  // radius: focal length (80.5 px / tan 15 deg) * 0.1 m / distance, the distance being the one
  // at which the bounding sphere (radius sqrt(3)/2) fills 92% of the image height.
  double sum_x = 0, sum_y = 0, count = 0;
  for (int py = 0; py < kHeight; ++py)
    for (int px = 0; px < kWidth; ++px)
      if (!is_background(pixel(rgb, kWidth, px, py), spec)) sum_x += px + 0.5, sum_y += py + 0.5, ++count;
  const double focal = 0.5 * kHeight / std::tan(15 * M_PI / 180);
  const double distance = std::sqrt(3.0) / 2 / std::sin(std::atan(0.92 * 0.5 * kHeight / focal));
  const double radius_px = focal * 0.1 / distance;  // about 8.3
  EXPECT_NEAR(sum_x / count, 0.5 * kWidth, 0.01);   // symmetric about the centre
  EXPECT_NEAR(sum_y / count, 0.5 * kHeight, 0.01);
  EXPECT_NEAR(std::sqrt(count / M_PI), radius_px, 0.3);  // pixel-centre sampling of the edge
  // Far away: untouched background.
  EXPECT_TRUE(is_background(pixel(rgb, kWidth, 5, 5), spec));
  EXPECT_TRUE(is_background(pixel(rgb, kWidth, kWidth - 5, kHeight - 5), spec));

  // The centre pixel's centre is the disc centre, where the sphere's normal points at the
  // camera, n = (0, 0, 1): colour = base * (ambient + diffuse * L.z) + 255 * specular * H.z^32.
  // Tolerance 1: the renderer computes in float and rounds to 8 bits.
  const pbf::Rgb base = pbf::Colormap("viridis")(value);
  using S = pbf::SphereShading;
  const double half_z = (S::light[2] + 1) / std::sqrt(S::light[0] * S::light[0] + S::light[1] * S::light[1] +
                                                      (S::light[2] + 1) * (S::light[2] + 1));
  const double shine = 255 * S::specular * std::pow(half_z, S::shininess);
  const unsigned char* centre = pixel(rgb, kWidth, 100, 80);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(centre[c], std::min(255.0, base[c] * (S::ambient + S::diffuse * S::light[2]) + shine), 1)
        << "channel " << c;
}

TEST(ImageRenderer, NearerParticleHidesFartherOne) {
  const ImageSpec spec = plain_spec(0.1);
  const ImageRenderer renderer(spec);
  // Both on the view line (the y axis through the centre); the camera is at y < 0. Listed
  // nearer-second and nearer-first, so neither drawing order nor index decides.
  for (int nearer : {0, 1}) {
    const real x[2] = {0.5, 0.5}, z[2] = {0.5, 0.5};
    const real y[2] = {real(nearer == 0 ? 0.3 : 0.7), real(nearer == 0 ? 0.7 : 0.3)};
    const double value[2] = {nearer == 0 ? 0.0 : 1.0, nearer == 0 ? 1.0 : 0.0};  // the nearer one is 0: purple
    std::vector<unsigned char> rgb;
    renderer.render(unit_box(), x, y, z, value, 2, 0.0, 1.0, "", rgb);
    const unsigned char* centre = pixel(rgb, kWidth, 100, 80);
    EXPECT_LT(centre[1], 60) << "nearer particle " << nearer;  // viridis 0 (68, 1, 84), not 1 (253, 231, 37)
    EXPECT_GT(centre[2], centre[1]) << "nearer particle " << nearer;
  }
}

// A camera placed by position: it looks at the centre, so a particle at the centre lands in
// the image centre, and its disc's radius follows the distance (half as far, twice as large).
TEST(ImageRenderer, CameraPositionSetsViewAndDistance) {
  auto disc_radius = [](double distance) {
    ImageSpec spec = plain_spec(0.05);
    spec.direction = {0, 0, 1};          // unused once a position is given
    spec.eye = std::array<double, 3>{0.5 + distance, 0.5, 0.5};  // on the +x side, looking along -x
    const ImageRenderer renderer(spec);
    const real x = 0.5, y = 0.5, z = 0.5;
    const double value = 0.5;
    std::vector<unsigned char> rgb;
    renderer.render(unit_box(), &x, &y, &z, &value, 1, 0.0, 1.0, "", rgb);
    double sum_x = 0, sum_y = 0, count = 0;
    for (int py = 0; py < kHeight; ++py)
      for (int px = 0; px < kWidth; ++px)
        if (!is_background(pixel(rgb, kWidth, px, py), spec)) sum_x += px + 0.5, sum_y += py + 0.5, ++count;
    EXPECT_NEAR(sum_x / count, 0.5 * kWidth, 0.01);
    EXPECT_NEAR(sum_y / count, 0.5 * kHeight, 0.01);
    return std::sqrt(count / M_PI);
  };
  const double focal = 0.5 * kHeight / std::tan(15 * M_PI / 180);
  EXPECT_NEAR(disc_radius(2.0), focal * 0.05 / 2.0, 0.3);  // about 7.5 px
  EXPECT_NEAR(disc_radius(1.0), focal * 0.05 / 1.0, 0.3);  // about 15 px
  ImageSpec looking_up = plain_spec(0.05);
  looking_up.eye = std::array<double, 3>{0.5, 0.5, -3};  // straight below: along 'up'
  std::vector<unsigned char> rgb;
  const real c = 0.5;
  const double v = 0;
  EXPECT_THROW(ImageRenderer(looking_up).render(unit_box(), &c, &c, &c, &v, 1, 0, 1, "", rgb), pbf::Error);
}

TEST(ImageRenderer, NanIsGreyAndValuesClamp) {
  const ImageSpec spec = plain_spec(0.1);
  const ImageRenderer renderer(spec);
  const real x = 0.5, y = 0.5, z = 0.5;
  std::vector<unsigned char> nan_image, high_image, top_image;
  const double nan = std::nan(""), high = 7.0, top = 1.0;
  renderer.render(unit_box(), &x, &y, &z, &nan, 1, 0.0, 1.0, "", nan_image);
  renderer.render(unit_box(), &x, &y, &z, &high, 1, 0.0, 1.0, "", high_image);
  renderer.render(unit_box(), &x, &y, &z, &top, 1, 0.0, 1.0, "", top_image);
  const unsigned char* grey = pixel(nan_image, kWidth, 100, 80);
  EXPECT_EQ(grey[0], grey[1]);
  EXPECT_EQ(grey[1], grey[2]);
  EXPECT_EQ(high_image, top_image);
}

TEST(ImageRenderer, SameBytesOnOneAndTwoThreads) {
  ImageSpec spec;  // the defaults: oblique view, box, colour bar, text
  spec.radius = 0.012;
  spec.label = "speed (m/s)";
  const ImageRenderer renderer(spec);
  const Domain domain{{0, 0, 0}, {1, 0.5, 0.8}};
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  const std::size_t n = 5000;
  std::vector<real> x(n), y(n), z(n);
  std::vector<double> value(n);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = real(u(rng)), y[i] = real(0.5 * u(rng)), z[i] = real(0.4 * u(rng));
    value[i] = 3 * u(rng);
  }
  y[0] = y[1], x[0] = x[1], z[0] = z[1];  // two coincident particles: a depth tie everywhere
  std::vector<unsigned char> one, two;
  renderer.render(domain, x.data(), y.data(), z.data(), value.data(), n, 0.0, 2.5, "t = 1.250 s", one);
  omp_set_num_threads(2);
  renderer.render(domain, x.data(), y.data(), z.data(), value.data(), n, 0.0, 2.5, "t = 1.250 s", two);
  omp_set_num_threads(1);
  EXPECT_TRUE(one == two);
}

TEST(ImageRenderer, WritePngWritesAPngFile) {
  const auto dir = pbf::test::temp_dir("image");
  std::vector<unsigned char> rgb(32 * 20 * 3, 128);
  const auto path = dir / "a.png";
  pbf::write_png(path.string(), 32, 20, rgb);
  const std::string bytes = pbf::test::read_file(path);
  ASSERT_GE(bytes.size(), 8u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_THROW(pbf::write_png((dir / "no-such-dir" / "a.png").string(), 32, 20, rgb), pbf::Error);
  EXPECT_THROW(pbf::write_png(path.string(), 33, 20, rgb), pbf::Error);  // wrong size
  std::filesystem::remove_all(dir);
}

TEST(ImageRenderer, BadSpecIsAnError) {
  auto expect_error = [](ImageSpec spec, const std::string& names) {
    try {
      ImageRenderer renderer(spec);
      ADD_FAILURE() << "no error for " << names;
    } catch (const pbf::Error& e) {
      EXPECT_NE(std::string(e.what()).find(names), std::string::npos) << e.what();
    }
  };
  const ImageSpec good = plain_spec(0.01);
  ImageSpec s = good;
  s.width = 15;
  expect_error(s, "width");
  s = good, s.height = 9000;
  expect_error(s, "height");
  s = good, s.zoom = 0;
  expect_error(s, "zoom");
  s = good, s.radius = 0;
  expect_error(s, "radius");
  s = good, s.direction = {0, 0, 0};
  expect_error(s, "direction");
  s = good, s.direction = {0, 0, -2};
  expect_error(s, "parallel");
  s = good, s.colormap = "rainbow";
  expect_error(s, "viridis");

  const ImageRenderer renderer(good);
  std::vector<unsigned char> rgb;
  const real p = 0.5;
  const double v = 1;
  EXPECT_THROW(renderer.render(unit_box(), &p, &p, &p, &v, 1, 1.0, 1.0, "", rgb), pbf::Error);  // vmin = vmax
}

TEST(ImageRenderer, ColorbarTicksAreThreeToFiveValuesInRange) {
  for (auto [lo, hi] :
       {std::pair{0.0, 2.37}, {0.0, 1.0}, {-1.0, 1.0}, {0.013, 0.0175}, {1e20, 1e20 + 1e6}, {5.0, 5.9}}) {
    const auto ticks = pbf::colorbar_ticks(lo, hi);
    EXPECT_GE(ticks.size(), 3u) << lo << " " << hi;
    EXPECT_LE(ticks.size(), 5u) << lo << " " << hi;
    for (double t : ticks) EXPECT_TRUE(t >= lo - 1e-9 * (hi - lo) && t <= hi + 1e-9 * (hi - lo)) << t;
  }
  EXPECT_EQ(pbf::colorbar_ticks(0, 1), (std::vector<double>{0, 0.25, 0.5, 0.75, 1}));
  EXPECT_EQ(pbf::colorbar_ticks(0, 2), (std::vector<double>{0, 0.5, 1, 1.5, 2}));
}

TEST(ImageRenderer, TinyImageWithOverlaysStaysInside) {
  ImageSpec spec;  // a colour bar and label wider than the image: clipped, not out of bounds
  spec.width = spec.height = 16;
  spec.radius = 0.05;
  spec.label = "a long label, ρ (kg/m³)";
  const ImageRenderer renderer(spec);
  const real p = 0.5;
  const double v = 0.5;
  std::vector<unsigned char> rgb;
  renderer.render(unit_box(), &p, &p, &p, &v, 1, 0.0, 1.0, "t = 0.000 s", rgb);
  EXPECT_EQ(rgb.size(), 16u * 16u * 3u);
}

// Solids in the image renderer: a container shows its far walls and floor but not its near
// walls, so the fluid inside stays in view; an obstacle shows its front; the grey is the
// Lambert shade of the side seen; a camera inside a closed container sees walls at every
// pixel (clipping at the near plane, no cracks between triangles); huge triangles are
// clipped; the bytes are the same at any thread count; a bad mesh is an error.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "engine/core/error.hpp"
#include "engine/render/image_renderer.hpp"
#include "test_solids.hpp"

using namespace pbf;
using pbf::test::box_mesh;

namespace {

// Looking along +y at the unit box's centre (as in test_image_renderer.cpp): world x is to
// the right, world z up; the centre of pixel (100, 80) is the domain centre.
constexpr int kWidth = 201, kHeight = 161;
ImageSpec side_spec() {
  ImageSpec spec;
  spec.width = kWidth;
  spec.height = kHeight;
  spec.direction = {0, 1, 0};
  spec.radius = 0.1;
  spec.draw_box = false;
  spec.colorbar = false;
  spec.axes = false;
  spec.scale_bar = false;
  return spec;
}

using Pixel = std::array<int, 3>;
Pixel at(const std::vector<unsigned char>& rgb, int x, int y) {
  const unsigned char* p = &rgb[(static_cast<std::size_t>(y) * kWidth + x) * 3];
  return {p[0], p[1], p[2]};
}
bool is_grey(const Pixel& p) { return p[0] == p[1] && p[1] == p[2] && p[0] != 255; }

// The shade of a surface whose visible normal, in camera axes (x right, y up, z toward the
// viewer), is n.
int shade(const std::array<double, 3>& n) {
  const float* L = SphereShading::light;
  const double lambert = std::max(0.0, L[0] * n[0] + L[1] * n[1] + L[2] * n[2]);
  return static_cast<int>(SolidShading::grey * (SphereShading::ambient + SphereShading::diffuse * lambert) + 0.5);
}

// The pixel where the side camera sees world point (x, y, z): the same projection as the
// renderer, from the distance at which the unit box's bounding sphere fills 92% of the height.
std::pair<int, int> side_pixel(double x, double y, double z) {
  const double focal = 0.5 * kHeight / std::tan(15 * M_PI / 180);
  const double distance = std::sqrt(3.0) / 2 / std::sin(std::atan(0.92 * 0.5 * kHeight / focal));
  const double depth = y - (0.5 - distance);
  return {int(std::floor(0.5 * kWidth + focal * (x - 0.5) / depth)),
          int(std::floor(0.5 * kHeight - focal * (z - 0.5) / depth))};
}

struct Scene {
  std::vector<real> x, y, z;
  std::vector<double> value;
  void add(double px, double py, double pz) { x.push_back(px), y.push_back(py), z.push_back(pz), value.push_back(0.5); }
  std::vector<unsigned char> render(const ImageSpec& spec, const std::vector<SolidSurface>& solids) const {
    std::vector<unsigned char> rgb;
    ImageRenderer(spec).render(Domain{}, x.data(), y.data(), z.data(), value.data(), x.size(), 0.0, 1.0, "", rgb,
                               solids);
    return rgb;
  }
};

}  // namespace

TEST(SolidImage, AContainerShowsItsFarWallAndTheFluidInsideAnObstacleHidesIt) {
  const TriangleMesh box = box_mesh({0.2, 0.2, 0.2}, {0.8, 0.8, 0.8});
  Scene scene;
  scene.add(0.5, 0.5, 0.5);
  const Pixel wall{shade({0, 0, 1}), shade({0, 0, 1}), shade({0, 0, 1})};  // a wall facing the camera
  const auto [cx, cy] = side_pixel(0.5, 0.5, 0.5);
  const auto [wx, wy] = side_pixel(0.3, 0.8, 0.3);  // the far wall, beside the particle

  const auto container = scene.render(side_spec(), {{&box, true}});
  EXPECT_FALSE(is_grey(at(container, cx, cy))) << "the near wall hides the particle";
  EXPECT_EQ(at(container, wx, wy), wall);
  const auto obstacle = scene.render(side_spec(), {{&box, false}});
  EXPECT_EQ(at(obstacle, cx, cy), wall);  // the near face, in front of the particle
  EXPECT_EQ(at(obstacle, wx, wy), wall);

  const auto none = scene.render(side_spec(), {});
  EXPECT_EQ(at(none, wx, wy), (Pixel{255, 255, 255}));
  EXPECT_EQ(at(none, cx, cy), at(container, cx, cy));
}

TEST(SolidImage, SeenFromAboveAContainerShowsItsFloorNotItsLid) {
  ImageSpec spec = side_spec();
  spec.direction = {0, 0.3, -1};  // from above, a little tilted
  spec.up = {0, 1, 0};
  const TriangleMesh box = box_mesh({0.2, 0.2, 0.2}, {0.8, 0.8, 0.8});
  Scene scene;
  scene.add(0.5, 0.5, 0.3);  // on the floor, in the middle
  const auto rgb = scene.render(spec, {{&box, true}});
  // The floor's inside (normal +z) in camera axes: right = forward x (0, 1, 0) = (-f_z, 0, f_x)
  // normalised, up' = right x forward.
  const double f[3] = {0, 0.3 / std::hypot(0.3, 1.0), -1 / std::hypot(0.3, 1.0)};
  const double r[3] = {-f[2] / std::hypot(f[2], f[0]), 0, f[0] / std::hypot(f[2], f[0])};
  const double u[3] = {r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0]};
  const int floor_grey = shade({r[2], u[2], -f[2]});
  // The image centre looks at the domain centre (0.5, 0.5, 0.5); the particle is below it,
  // on the floor, and covers the centre pixel: the lid is not drawn over it.
  EXPECT_FALSE(is_grey(at(rgb, kWidth / 2, kHeight / 2)));
  // Left and right of the particle (about 8 pixels in radius), the floor: the centre row meets
  // it near y = 0.6, where 14 pixels are about 0.19 m.
  for (int x : {kWidth / 2 - 14, kWidth / 2 + 14})
    EXPECT_EQ(at(rgb, x, kHeight / 2), (Pixel{floor_grey, floor_grey, floor_grey})) << x;
  EXPECT_EQ(at(rgb, 3, 3), (Pixel{255, 255, 255}));  // outside the box
}

TEST(SolidImage, ACameraInsideAClosedContainerSeesWallsAtEveryPixel) {
  const TriangleMesh box = box_mesh({0.2, 0.2, 0.2}, {0.8, 0.8, 0.8});
  Scene scene;
  for (double zoom : {1.0, 0.25}) {  // 0.25: a wide angle, walls cut by the near plane all around
    ImageSpec spec = side_spec();
    spec.eye = {0.25, 0.26, 0.75};
    spec.center = {0.8, 0.7, 0.2};
    spec.zoom = zoom;
    const auto rgb = scene.render(spec, {{&box, true}});
    int holes = 0;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) holes += !is_grey(at(rgb, x, y));
    EXPECT_EQ(holes, 0) << "zoom " << zoom;
    // Seen from inside, an obstacle shows nothing: all its faces look away.
    const auto obstacle = scene.render(spec, {{&box, false}});
    EXPECT_EQ(at(obstacle, kWidth / 2, kHeight / 2), (Pixel{255, 255, 255}));
  }
}

TEST(SolidImage, HugeTrianglesAndTrianglesBehindTheCameraAreClipped) {
  TriangleMesh ground;  // a plane 2e7 m wide under the domain, facing up
  ground.vertices = {{-1e7, -1e7, -0.1}, {1e7, -1e7, -0.1}, {1e7, 1e7, -0.1}, {-1e7, 1e7, -0.1}};
  ground.triangles = {{0, 1, 2}, {0, 2, 3}};
  TriangleMesh behind = box_mesh({0.4, -50, 0.4}, {0.6, -40, 0.6});  // behind the side camera
  ImageSpec spec = side_spec();
  spec.direction = {0, 1, -0.2};  // the horizon just above the middle of the image
  Scene scene;
  const auto rgb = scene.render(spec, {{&ground, false}, {&behind, false}});
  // The horizon is 0.2 focal lengths (about 60 pixels) above the centre, near row 20: the sky
  // above it, the ground everywhere below.
  const Pixel ground_grey = at(rgb, kWidth / 2, kHeight - 1);
  EXPECT_TRUE(is_grey(ground_grey));
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      if (y <= 10) EXPECT_EQ(at(rgb, x, y), (Pixel{255, 255, 255})) << x << ", " << y;
      if (y >= 30) EXPECT_EQ(at(rgb, x, y), ground_grey) << x << ", " << y;
    }
}

TEST(SolidImage, SameBytesOnOneAndTwoThreads) {
  ImageSpec spec;  // the defaults: oblique view, box, colour bar
  spec.radius = 0.02;
  const TriangleMesh tank = box_mesh({0.05, 0.05, 0.05}, {0.95, 0.95, 0.95});
  const TriangleMesh block = box_mesh({0.3, 0.3, 0.1}, {0.6, 0.5, 0.4});
  Scene scene;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.1, 0.9);
  for (int i = 0; i < 3000; ++i) scene.add(u(rng), u(rng), 0.5 * u(rng));
  const std::vector<SolidSurface> solids{{&tank, true}, {&block, false}, {&block, false}};  // a tie everywhere
  const auto one = scene.render(spec, solids);
  omp_set_num_threads(2);
  const auto two = scene.render(spec, solids);
  omp_set_num_threads(3);
  const auto three = scene.render(spec, solids);
  omp_set_num_threads(1);
  EXPECT_TRUE(one == two);
  EXPECT_TRUE(one == three);
  EXPECT_TRUE(std::any_of(one.begin(), one.end(), [](unsigned char c) { return c != 255; }));
}

TEST(SolidImage, ATriangleNamingAMissingVertexIsAnError) {
  TriangleMesh bad = box_mesh({0.2, 0.2, 0.2}, {0.8, 0.8, 0.8});
  bad.triangles[5][1] = 8;
  Scene scene;
  try {
    scene.render(side_spec(), {{&bad, true}});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("triangle 5 of solid surface 1 names vertex 8"), std::string::npos)
        << e.what();
  }
}

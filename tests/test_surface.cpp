// Surface reconstruction (engine/surface): the marching-cubes table, and meshes of particle
// clouds whose surface is known: a resting column in a box, a sphere, a lone droplet.
#include <omp.h>

#include <barrier>
#include <map>
#include <cmath>
#include <numbers>
#include <thread>

#include <gtest/gtest.h>

#include "engine/core/error.hpp"
#include "engine/render/image_renderer.hpp"
#include "engine/surface/cube_cases.hpp"
#include "engine/surface/surface.hpp"
#include "tests/surface_checks.hpp"

namespace pbf {
namespace {

using namespace surface_checks;

const char* name(SurfaceKernel k) {
  return k == SurfaceKernel::anisotropic ? "anisotropic" : (k == SurfaceKernel::isotropic ? "isotropic" : "spheres");
}

TEST(CubeCases, EveryCaseIsClosedAgainstItsNeighboursAndPointsOut) {
  const CubeCases& cases = cube_cases();
  EXPECT_EQ(cases.triangles[0], 0);
  EXPECT_EQ(cases.triangles[255], 0);
  int most = 0;
  for (int mask = 1; mask < 255; ++mask) {
    most = std::max(most, int(cases.triangles[mask]));
    ASSERT_GT(cases.triangles[mask], 0) << mask;
    // Each triangle's normal (vertices at the edges' midpoints) points from the inside corners
    // to the outside ones: summed over the case, along (outside centroid - inside centroid).
    Vec normal{0, 0, 0}, in{0, 0, 0}, out{0, 0, 0};
    for (int c = 0; c < 8; ++c) {
      const Vec p{double(c & 1), double((c >> 1) & 1), double((c >> 2) & 1)};
      Vec& side = ((mask >> c) & 1) ? in : out;
      for (int a = 0; a < 3; ++a) side[a] += p[a] / std::popcount(unsigned(((mask >> c) & 1) ? mask : 255 - mask));
    }
    for (int t = 0; t < cases.triangles[mask]; ++t) {
      Vec v[3];
      for (int k = 0; k < 3; ++k) {
        const int e = cases.edges[mask][3 * t + k], c = edge_corner(e);
        v[k] = {double(c & 1), double((c >> 1) & 1), double((c >> 2) & 1)};
        v[k][edge_axis(e)] += 0.5;
      }
      const Vec n = cross(sub(v[1], v[0]), sub(v[2], v[0]));
      for (int a = 0; a < 3; ++a) normal[a] += n[a];
    }
    // Cases whose inside and outside corners have the same centroid (diagonal pairs) say nothing.
    const Vec d = sub(out, in);
    if (dot(d, d) > 1e-9) {
      EXPECT_GT(dot(normal, d), 0) << "case " << mask;
    }
  }
  EXPECT_LE(most, 5);  // Lorensen & Cline's table has at most five
  // No triangle lies flat on a face of the cube: the neighbour's would lie on it, back to back.
  for (int mask = 1; mask < 255; ++mask)
    for (int t = 0; t < cases.triangles[mask]; ++t) {
      int common = 0x3f;  // faces (axis, side) as bits 2 axis + side
      for (int k = 0; k < 3; ++k) {
        const int e = cases.edges[mask][3 * t + k], c = edge_corner(e);
        int faces = 0;
        for (int axis = 0; axis < 3; ++axis)
          if (axis != edge_axis(e)) faces |= 1 << (2 * axis + ((c >> axis) & 1));
        common &= faces;
      }
      EXPECT_EQ(common, 0) << "case " << mask << " triangle " << t;
    }
}

// A lattice of particles at spacing s, sites (i + 1/2) s, filling [lo, lo + counts s).
SurfaceCloud lattice(double s, const int counts[3], const double lo[3] = nullptr) {
  SurfaceCloud c;
  for (int k = 0; k < counts[2]; ++k)
    for (int j = 0; j < counts[1]; ++j)
      for (int i = 0; i < counts[0]; ++i) {
        c.x.push_back(real((lo ? lo[0] : 0) + (i + 0.5) * s));
        c.y.push_back(real((lo ? lo[1] : 0) + (j + 0.5) * s));
        c.z.push_back(real((lo ? lo[2] : 0) + (k + 0.5) * s));
        c.volume.push_back(s * s * s);
      }
  return c;
}

SurfaceSettings settings_for(double s, const double hi[3]) {
  SurfaceSettings st;
  st.spacing = s;
  st.radius = 2 * s;
  st.voxel = s / 2;
  st.sphere_radius = 0.6 * s;
  for (int a = 0; a < 3; ++a) st.lo[a] = 0, st.hi[a] = hi[a];
  st.wall.fill(true);
  return st;
}

// A column at rest in a box: 12 x 8 particles across, 16 high, in a tank 12 x 8 x 30.
struct Column {
  double s = 0.01;
  int counts[3] = {12, 8, 16};
  double hi[3] = {0.12, 0.08, 0.30};
  SurfaceCloud cloud = lattice(s, counts);
};

TEST(Surface, RestingColumnIsOneClosedBodyOfItsLatticeVolumeWithAFlatTopAtItsHeight) {
  Column col;
  for (SurfaceKernel kernel : {SurfaceKernel::anisotropic, SurfaceKernel::isotropic, SurfaceKernel::spheres}) {
    SCOPED_TRACE(name(kernel));
    SurfaceSettings st = settings_for(col.s, col.hi);
    st.kernel = kernel;
    const SurfaceMesh m = reconstruct_surface(col.cloud, st);
    ASSERT_GT(m.mesh.triangles.size(), 0u);
    EXPECT_EQ(manifold_defect(m.mesh), "");
    const double lattice_volume = double(col.cloud.size()) * col.s * col.s * col.s;
    std::printf("column (%s): volume %.4f of the lattice's\n", name(kernel), enclosed_volume(m.mesh) / lattice_volume);
    EXPECT_NEAR(enclosed_volume(m.mesh) / lattice_volume, 1, 0.02);
    // The top, away from the walls (more than R from them): flat and at the column's height.
    const double height = col.counts[2] * col.s;
    double worst_angle = 0, worst_height = 0;
    int top = 0;
    for (std::size_t v = 0; v < m.mesh.vertices.size(); ++v) {
      const auto& x = m.mesh.vertices[v];
      if (x[2] < height - 2 * col.s) continue;
      if (x[0] < st.radius || x[0] > col.hi[0] - st.radius || x[1] < st.radius || x[1] > col.hi[1] - st.radius) continue;
      ++top;
      worst_angle = std::max(worst_angle, std::acos(std::min(1.0, double(m.normals[v][2]))) * 180 / std::numbers::pi);
      worst_height = std::max(worst_height, std::fabs(x[2] - height));
    }
    EXPECT_GT(top, 20);
    EXPECT_LT(worst_angle, 5.0);
    EXPECT_LT(worst_height, col.s / 4);
    EXPECT_EQ(self_intersections(m.mesh, col.s), 0u);
  }
}

TEST(Surface, OpenWallsLeaveOnlyTheFreeSurface) {
  Column col;
  SurfaceSettings st = settings_for(col.s, col.hi);
  st.walls = SurfaceWalls::open;
  const SurfaceMesh m = reconstruct_surface(col.cloud, st);
  EXPECT_EQ(manifold_defect(m.mesh, true), "");
  // The free surface is the top, facing up, and covers the tank's floor plan once (its area
  // projected on the floor), up to the walls.
  double projected = 0;
  for (const auto& t : m.mesh.triangles) {
    const Vec n = cross(sub(m.mesh.vertices[t[1]], m.mesh.vertices[t[0]]), sub(m.mesh.vertices[t[2]], m.mesh.vertices[t[0]]));
    projected += 0.5 * n[2];
    EXPECT_GT(n[2], 0);
  }
  EXPECT_NEAR(projected / (col.hi[0] * col.hi[1]), 1, 0.01);
}

// A ball of particles as a droplet at rest arranges them: shells a spacing apart (radii
// (k + 1/2) s), each with as many particles as its area holds (4 pi r^2 / s^2), spread evenly
// over it (a Fibonacci lattice). A cubic lattice cut to a sphere would be a terraced ball.
SurfaceCloud ball(double s, double r, const Vec& centre) {
  SurfaceCloud c;
  const double golden = std::numbers::pi * (3 - std::sqrt(5.0));
  for (int k = 0; (k + 0.5) * s < r; ++k) {
    const double shell = (k + 0.5) * s;
    const int count = std::max(1, int(std::lround(4 * std::numbers::pi * shell * shell / (s * s))));
    for (int i = 0; i < count; ++i) {
      const double z = count == 1 ? 0 : 1 - 2 * (i + 0.5) / count, ring = std::sqrt(1 - z * z), phi = golden * i;
      c.x.push_back(real(centre[0] + shell * ring * std::cos(phi)));
      c.y.push_back(real(centre[1] + shell * ring * std::sin(phi)));
      c.z.push_back(real(centre[2] + shell * z));
      c.volume.push_back(s * s * s);
    }
  }
  return c;
}

// Along a periodic axis the fluid runs on across the faces: a layer in a domain periodic along
// x, 16 spacings long, 8 layers deep over half its length and 4 over the other (two steps, one
// of them on the faces), meshed as placed and shifted by 4 spacings along x (wrapped). Its top
// is the same surface moved: at every voxel column the top's height is the shifted layer's,
// the columns next to the faces included (mirrored there instead of wrapped, the step on the
// faces would be a flat top), and each encloses the lattice's volume (the faces close it).
TEST(Surface, APeriodicLayerRunsOnAcrossItsFaces) {
  const double s = 0.01, hi[3] = {0.16, 0.08, 0.16};
  SurfaceSettings st = settings_for(s, hi);
  st.periodic[0] = true;
  auto layer = [&](int shift) {
    SurfaceCloud c;
    for (int i = 0; i < 16; ++i)
      for (int j = 0; j < 8; ++j)
        for (int k = 0; k < (i < 8 ? 8 : 4); ++k) {
          c.x.push_back(real(((i + shift) % 16 + 0.5) * s)), c.y.push_back(real((j + 0.5) * s));
          c.z.push_back(real((k + 0.5) * s)), c.volume.push_back(s * s * s);
        }
    return c;
  };
  // The top's height over each voxel column (its vertices on vertical edges, facing up).
  const double v = st.voxel;
  auto heights = [&](const SurfaceMesh& m) {
    std::map<std::pair<long, long>, double> top;
    for (std::size_t k = 0; k < m.mesh.vertices.size(); ++k) {
      const auto& x = m.mesh.vertices[k];
      const double i = x[0] / v - 0.5, j = x[1] / v - 0.5;
      if (m.normals[k][2] < 0.5 || std::fabs(i - std::round(i)) > 1e-4 || std::fabs(j - std::round(j)) > 1e-4) continue;
      auto& z = top[{std::lround(i), std::lround(j)}];
      z = std::max(z, x[2]);
    }
    return top;
  };
  const SurfaceCloud placed = layer(0), shifted = layer(4);
  const SurfaceMesh a = reconstruct_surface(placed, st), b = reconstruct_surface(shifted, st);
  const double lattice_volume = double(placed.size()) * s * s * s;
  for (const SurfaceMesh* m : {&a, &b}) {
    EXPECT_EQ(manifold_defect(m->mesh), "");
    EXPECT_NEAR(enclosed_volume(m->mesh) / lattice_volume, 1, 0.02);
  }
  const auto top_a = heights(a), top_b = heights(b);
  const long n = std::lround(hi[0] / v), moved = std::lround(4 * s / v);
  int compared = 0, next_to_a_face = 0;
  for (const auto& [column, z] : top_a) {
    const auto other = top_b.find({(column.first + moved) % n, column.second});
    ASSERT_NE(other, top_b.end()) << column.first << " " << column.second;
    EXPECT_NEAR(other->second, z, 1e-5) << "column " << column.first << " " << column.second;
    ++compared;
    next_to_a_face += column.first == 0 || column.first == n - 1;
  }
  EXPECT_GT(compared, 300);
  EXPECT_GT(next_to_a_face, 20);
}

TEST(Surface, SphereHasItsRadiusAndNoBumpsAtParticleScale) {
  const double s = 0.01, r = 0.1, box[3] = {0.4, 0.4, 0.4};
  const Vec centre{0.2, 0.2, 0.2};
  const SurfaceCloud cloud = ball(s, r, centre);
  for (SurfaceKernel kernel : {SurfaceKernel::anisotropic, SurfaceKernel::isotropic, SurfaceKernel::spheres}) {
    SCOPED_TRACE(name(kernel));
    SurfaceSettings st = settings_for(s, box);
    st.kernel = kernel;
    const SurfaceMesh m = reconstruct_surface(cloud, st);
    EXPECT_EQ(manifold_defect(m.mesh), "");
    EXPECT_EQ(self_intersections(m.mesh, s), 0u);
    // The sphere of the particles' volume.
    const double radius = std::cbrt(3 * double(cloud.size()) * s * s * s / (4 * std::numbers::pi));
    double mean = 0;
    for (const auto& x : m.mesh.vertices) mean += std::sqrt(dot(sub(x, centre), sub(x, centre)));
    mean /= double(m.mesh.vertices.size());
    EXPECT_NEAR(mean, radius, s / 2);
    // Mean curvature at each vertex: sum_j 2 n_i.(x_i - x_j) / sum_j |x_i - x_j|^2 over its edges
    // (1/R exactly on a sphere; weighed by the edges' squared lengths, so that the tiny edges
    // marching cubes makes near a voxel's corner do not dominate): its spread times R, and the
    // normals' angle from the radius.
    const std::size_t nv = m.mesh.vertices.size();
    std::vector<double> bend(nv, 0), length2(nv, 0);
    for (const auto& t : m.mesh.triangles)
      for (int k = 0; k < 3; ++k) {
        const auto i = t[k], j = t[(k + 1) % 3];
        const Vec d = sub(m.mesh.vertices[i], m.mesh.vertices[j]);
        const Vec ni{m.normals[i][0], m.normals[i][1], m.normals[i][2]}, nj{m.normals[j][0], m.normals[j][1], m.normals[j][2]};
        bend[i] += 2 * dot(ni, d), length2[i] += dot(d, d);
        bend[j] -= 2 * dot(nj, d), length2[j] += dot(d, d);
      }
    double h_mean = 0, h_var = 0;
    std::vector<double> angles;
    for (std::size_t v = 0; v < nv; ++v) {
      const double h = bend[v] / length2[v] * mean;
      h_mean += h / double(nv);
      h_var += h * h / double(nv);
      const Vec radial = sub(m.mesh.vertices[v], centre);
      const Vec n{m.normals[v][0], m.normals[v][1], m.normals[v][2]};
      angles.push_back(std::acos(std::min(1.0, dot(n, radial) / std::sqrt(dot(radial, radial)))) * 180 / std::numbers::pi);
    }
    std::sort(angles.begin(), angles.end());
    const double spread = std::sqrt(std::max(0.0, h_var - h_mean * h_mean));
    const double angle99 = angles[angles.size() * 99 / 100], worst_angle = angles.back();
    std::printf("sphere (%s): radius %.4f m (particles' %.4f), H R mean %.3f spread %.3f, normals off the radius: "
                "99%% within %.1f deg, worst %.1f deg\n",
                name(kernel), mean, radius, h_mean, spread,
                angle99, worst_angle);
    // Bumps at the particles' scale (wavelength 2 s) of height A bend the surface by about
    // A (pi / s)^2: a spread of H R below 1.5 keeps them below 1.5 s^2 / (pi^2 R) = 0.015 s here.
    EXPECT_NEAR(h_mean, 1, 0.15);
    EXPECT_LT(spread, 1.5);
    EXPECT_LT(angle99, 10);
  }
}

TEST(Surface, LoneParticleIsADropletAndAnEmptyFrameAnEmptyMesh) {
  const double s = 0.01, box[3] = {0.2, 0.2, 0.2};
  SurfaceCloud one;
  one.x = {real(0.1)}, one.y = {real(0.1)}, one.z = {real(0.1)}, one.volume = {s * s * s};
  const SurfaceMesh m = reconstruct_surface(one, settings_for(s, box));
  EXPECT_EQ(manifold_defect(m.mesh), "");
  const double r = std::cbrt(3 * enclosed_volume(m.mesh) / (4 * std::numbers::pi));
  EXPECT_GT(r, 0.4 * s);  // visible: about the particle's own sphere (0.62 s)
  EXPECT_LT(r, 0.7 * s);
  const SurfaceMesh empty = reconstruct_surface(SurfaceCloud{}, settings_for(s, box));
  EXPECT_TRUE(empty.mesh.triangles.empty());
}

TEST(Surface, SameBitsAtAnyThreadCount) {
  Column col;
  SurfaceCloud cloud = col.cloud;
  // Disturb the lattice so that every case of the table and every anisotropy turns up.
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    cloud.x[i] += real(0.3 * col.s * std::sin(double(i) * 1.7));
    cloud.z[i] += real(0.3 * col.s * std::sin(double(i) * 0.9));
  }
  cloud.attributes.push_back({"velocity", 3, std::vector<double>(3 * cloud.size())});
  for (std::size_t i = 0; i < cloud.attributes[0].values.size(); ++i) cloud.attributes[0].values[i] = std::cos(double(i));
  const SurfaceSettings st = settings_for(col.s, col.hi);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const SurfaceMesh one = reconstruct_surface(cloud, st);
  omp_set_num_threads(std::max(2, threads));
  const SurfaceMesh many = reconstruct_surface(cloud, st);
  omp_set_num_threads(threads);
  EXPECT_EQ(one.mesh.vertices, many.mesh.vertices);
  EXPECT_EQ(one.mesh.triangles, many.mesh.triangles);
  EXPECT_EQ(one.normals, many.normals);
  ASSERT_EQ(many.attributes.size(), 1u);
  EXPECT_EQ(one.attributes[0].values, many.attributes[0].values);
  EXPECT_EQ(manifold_defect(many.mesh), "");
  EXPECT_EQ(self_intersections(many.mesh, col.s), 0u);
}

// Parts that agree through a barrier, as ranks do through MPI (scene_surface).
struct Agreement {
  explicit Agreement(int parts) : barrier(parts), lists(parts), errors(parts) {}
  void agree(int r, std::vector<std::int64_t>& blocks, std::string& error) {
    lists[r] = blocks, errors[r] = error;
    barrier.arrive_and_wait();
    blocks.clear(), error.clear();
    for (std::size_t k = 0; k < lists.size(); ++k) {
      blocks.insert(blocks.end(), lists[k].begin(), lists[k].end());
      if (error.empty()) error = errors[k];
    }
    barrier.arrive_and_wait();  // before anyone's next round overwrites the lists
  }
  std::barrier<> barrier;
  std::vector<std::vector<std::int64_t>> lists;
  std::vector<std::string> errors;
};

TEST(Surface, SlabsMeshedApartJoinToTheWholeBitForBit) {
  // A slope of water 150 spacings long (from 20 layers high down to 4) with its particles
  // disturbed, and a blob and droplets flying above it, in a long tank.
  const double s = 0.01;
  const double hi[3] = {160 * s, 8 * s, 40 * s};
  SurfaceCloud cloud;
  auto add = [&](double x, double y, double z) {
    cloud.x.push_back(real(x)), cloud.y.push_back(real(y)), cloud.z.push_back(real(z));
    cloud.volume.push_back(s * s * s);
  };
  for (int i = 0; i < 150; ++i)
    for (int j = 0; j < 8; ++j)
      for (int k = 0; k < 20 - 16 * i / 150; ++k) {
        const double n = double(cloud.size());
        add((i + 0.5 + 0.2 * std::sin(1.7 * n)) * s, (j + 0.5) * s, (k + 0.5 + 0.2 * std::sin(0.9 * n)) * s);
      }
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 6; ++k) add((76 + i) * s, (2 + j) * s, (30 + k) * s);
  for (int d = 0; d < 12; ++d) add((10 + 12.3 * d) * s, 4 * s, (26 + (d % 3)) * s);
  cloud.attributes.push_back({"speed", 1, std::vector<double>(cloud.size())});
  for (std::size_t i = 0; i < cloud.size(); ++i) cloud.attributes[0].values[i] = std::cos(double(i));
  for (SurfaceWalls walls : {SurfaceWalls::closed, SurfaceWalls::open}) {
    SurfaceSettings st = settings_for(s, hi);
    st.walls = walls;
    const SurfaceMesh whole = reconstruct_surface(cloud, st);

    constexpr int kParts = 3;
    SurfaceSlabs slabs(st, false);
    ASSERT_EQ(slabs.axis, 0);
    std::vector<std::int64_t> count(static_cast<std::size_t>(slabs.layers), 0);
    for (std::size_t i = 0; i < cloud.size(); ++i) ++count[static_cast<std::size_t>(slabs.layer(cloud.x[i]))];
    slabs.cut(count, kParts);
    Agreement agreement(kParts);
    std::vector<SurfacePiece> pieces(kParts);
    std::vector<std::string> failed(kParts);
    std::vector<std::thread> parts;
    for (int r = 0; r < kParts; ++r) {
      SurfacePart part = slabs.part(r);
      EXPECT_LT(part.first, part.end) << "part " << r << " has no blocks";
      SurfaceCloud mine;  // the particles it needs, in the whole's order
      mine.attributes.push_back({"speed", 1, {}});
      for (std::size_t i = 0; i < cloud.size(); ++i)
        if (slabs.needs(r, cloud.x[i])) {
          mine.x.push_back(cloud.x[i]), mine.y.push_back(cloud.y[i]), mine.z.push_back(cloud.z[i]);
          mine.volume.push_back(cloud.volume[i]);
          mine.attributes[0].values.push_back(cloud.attributes[0].values[i]);
        }
      EXPECT_LT(mine.size(), cloud.size() * 3 / 5) << "part " << r << " needs nearly every particle";
      part.agree = [&agreement, r](std::vector<std::int64_t>& blocks, std::string& error) {
        agreement.agree(r, blocks, error);
      };
      parts.emplace_back([&, r, part, mine = std::move(mine)] {
        try {
          pieces[r] = reconstruct_surface_part(mine, st, part);
        } catch (const std::exception& e) {
          failed[r] = e.what();
        }
      });
    }
    for (auto& t : parts) t.join();
    for (int r = 0; r < kParts; ++r) ASSERT_EQ(failed[r], "") << "part " << r;
    const SurfaceMesh joined = join_surface_pieces(pieces, st);
    ASSERT_GT(whole.mesh.triangles.size(), 1000u);
    EXPECT_EQ(joined.mesh.vertices, whole.mesh.vertices);
    EXPECT_EQ(joined.mesh.triangles, whole.mesh.triangles);
    EXPECT_EQ(joined.normals, whole.normals);
    ASSERT_EQ(joined.attributes.size(), 1u);
    EXPECT_EQ(joined.attributes[0].values, whole.attributes[0].values);
    EXPECT_EQ(manifold_defect(joined.mesh, walls == SurfaceWalls::open), "");
  }
}

TEST(Surface, VelocityOnTheVerticesIsTheFluids) {
  Column col;
  SurfaceCloud cloud = col.cloud;
  // A shear: w = x (m/s per m; along the side walls x = 0 and x = L, which mirror only u): a
  // vertex at x should read about x. An average with weights is the value at the weights'
  // centroid, which for a vertex beyond the outer layer, at a corner, lies up to a spacing off.
  std::vector<double> v(3 * cloud.size(), 0.0);
  for (std::size_t i = 0; i < cloud.size(); ++i) v[2 * cloud.size() + i] = cloud.x[i];
  cloud.attributes.push_back({"velocity", 3, v});
  const SurfaceMesh m = reconstruct_surface(cloud, settings_for(col.s, col.hi));
  const std::size_t nv = m.mesh.vertices.size();
  double worst = 0;
  for (std::size_t k = 0; k < nv; ++k) {
    const double z = m.mesh.vertices[k][2];
    if (z < 2 * col.s) continue;  // away from the floor, which mirrors w
    worst = std::max(worst, std::fabs(m.attributes[0].values[2 * nv + k] - m.mesh.vertices[k][0]));
  }
  EXPECT_LT(worst, col.s);
}

TEST(Surface, BadSettingsNameTheParameterAndAHugeGridIsRefusedWithItsSize) {
  Column col;
  SurfaceSettings st = settings_for(col.s, col.hi);
  auto fails_with = [&](SurfaceSettings bad, const std::string& text) {
    try {
      reconstruct_surface(col.cloud, bad);
      ADD_FAILURE() << "no error for " << text;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  };
  SurfaceSettings bad = st;
  bad.voxel = 0;
  fails_with(bad, "'voxel'");
  bad = st, bad.radius = -1;
  fails_with(bad, "'radius'");
  bad = st, bad.radius = NAN;
  fails_with(bad, "'radius'");
  bad = st, bad.iso = 1.5;
  fails_with(bad, "'iso'");
  bad = st, bad.voxel = 1e-6;
  bad.memory_limit = 64.0 * (1 << 20);
  fails_with(bad, "MiB");
  bad = st, bad.radius = 10 * col.s, bad.voxel = col.s / 10;  // kernels 200 voxels across
  bad.memory_limit = 8.0 * (1 << 20);
  fails_with(bad, "to list the particles of its blocks");
  SurfaceCloud nan_cloud = col.cloud;
  nan_cloud.z[3] = real(NAN);
  try {
    reconstruct_surface(nan_cloud, st);
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("particle 3"), std::string::npos);
  }
}

// dump/image's draw = "surface": the column's mesh drawn as water. Seen from the side, the
// water's pixels are blue (the body colour) with a lighter sheen where the view grazes the
// surface (Fresnel); the picture is the same bytes at one and two threads.
TEST(SurfaceImage, TheColumnIsDrawnAsWaterWithASheenSameBytesAtAnyThreadCount) {
  Column col;
  SurfaceSettings st = settings_for(col.s, col.hi);
  const SurfaceMesh m = reconstruct_surface(col.cloud, st);
  ImageSpec spec;
  spec.width = 200, spec.height = 150, spec.radius = 1, spec.colorbar = false;
  spec.direction = {1, 2, -0.7};
  Domain domain;
  for (int a = 0; a < 3; ++a) domain.hi[a] = col.hi[a];
  const std::vector<SolidSurface> water{{&m.mesh, false, true, &m.normals}};
  const real none = 0;
  const double no_value = 0;
  std::vector<unsigned char> one, two;
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  ImageRenderer(spec).render(domain, &none, &none, &none, &no_value, 0, 0, 1, "", one, water);
  omp_set_num_threads(std::max(2, threads));
  ImageRenderer(spec).render(domain, &none, &none, &none, &no_value, 0, 0, 1, "", two, water);
  omp_set_num_threads(threads);
  EXPECT_TRUE(one == two);
  int blue = 0, lightest = 0, darkest = 255;
  for (std::size_t p = 0; p < one.size(); p += 3) {
    const int r = one[p], g = one[p + 1], b = one[p + 2];
    if (b > r + 30 && b >= g) {  // water: blue above red
      ++blue;
      lightest = std::max(lightest, r), darkest = std::min(darkest, r);
    }
  }
  EXPECT_GT(blue, 2000);              // the column fills a good part of the picture
  EXPECT_GT(lightest - darkest, 40);  // shaded: lit faces, grazing sheen and the shade differ
}

// The water's shading follows the mesh's normals across each triangle (Phong), so a smooth
// surface looks smooth: on a ball of water the colour varies about linearly from pixel to
// pixel (the second differences no more than rounding to whole levels makes, about 0.5), where
// shading each triangle flat (its corners all given the face's normal) shows the facets, a
// few pixels wide, as steps.
TEST(SurfaceImage, ABallOfWaterIsShadedWithoutFacets) {
  const double s = 0.01, r = 0.1, box[3] = {0.4, 0.4, 0.4};
  const SurfaceMesh m = reconstruct_surface(ball(s, r, {0.2, 0.2, 0.2}), settings_for(s, box));
  ImageSpec spec;
  spec.width = 240, spec.height = 240, spec.radius = 1, spec.colorbar = false, spec.scale_bar = false;
  spec.direction = {1, 2, -0.7};
  spec.zoom = 1.6;
  Domain domain;
  for (int a = 0; a < 3; ++a) domain.hi[a] = box[a];
  const real none = 0;
  const double no_value = 0;
  // How rough the shading is: the mean of |c(x - 1) - 2 c(x) + c(x + 1)| along rows (c the red
  // channel, the sheen's) over the water well inside the ball's outline (a disc of 70% of its
  // radius about the water's centroid): zero where the colour varies linearly, large at steps.
  auto roughness = [&](const std::vector<std::array<float, 3>>* normals) {
    std::vector<unsigned char> rgb;
    const std::vector<SolidSurface> water{{&m.mesh, false, true, normals}};
    ImageRenderer(spec).render(domain, &none, &none, &none, &no_value, 0, 0, 1, "", rgb, water);
    auto at = [&](int x, int y) { return (std::size_t(y) * spec.width + x) * 3; };
    auto is_water = [&](std::size_t p) { return rgb[p + 2] > rgb[p] + 30 && rgb[p + 2] >= rgb[p + 1]; };
    double cx = 0, cy = 0, count = 0;
    for (int y = 0; y < spec.height; ++y)
      for (int x = 0; x < spec.width; ++x)
        if (is_water(at(x, y))) cx += x, cy += y, count += 1;
    cx /= count, cy /= count;
    const double inner = 0.7 * std::sqrt(count / std::numbers::pi);
    double sum = 0, terms = 0;
    for (int y = 0; y < spec.height; ++y)
      for (int x = 1; x + 1 < spec.width; ++x)
        if (std::hypot(x - cx, y - cy) < inner) {
          sum += std::abs(int(rgb[at(x - 1, y)]) - 2 * int(rgb[at(x, y)]) + int(rgb[at(x + 1, y)]));
          terms += 1;
        }
    EXPECT_GT(terms, 3000);
    return sum / terms;
  };
  const double smooth = roughness(&m.normals), flat = roughness(nullptr);
  std::printf("ball of water: mean second difference along rows %.2f levels (Phong), %.2f (flat)\n", smooth, flat);
  EXPECT_LT(smooth, 1.5);
  EXPECT_GT(flat, 2 * smooth);
}

}  // namespace
}  // namespace pbf

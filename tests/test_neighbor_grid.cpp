// The neighbour grid against brute force: random, clustered (every particle in one cell),
// boundary-hugging and out-of-box particle sets, at 1 and 2 threads; and the cell cap.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <random>
#include <vector>

#include "engine/sph/neighbor_grid.hpp"

using namespace pbf;

namespace {

struct Cloud {
  std::vector<real> x, y, z;
  void add(double a, double b, double c) {
    x.push_back(real(a));
    y.push_back(real(b));
    z.push_back(real(c));
  }
};

void expect_matches_brute_force(const Cloud& p, const Domain& d, double h, int threads) {
  omp_set_num_threads(threads);
  NeighborGrid grid;
  grid.bin(p.x.data(), p.y.data(), p.z.data(), p.x.size(), d, h);
  grid.build_lists(p.x.data(), p.y.data(), p.z.data(), h);
  const real h2 = real(h * h);
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < p.x.size(); ++i) {
    std::vector<std::uint32_t> expected;
    for (std::size_t j = 0; j < p.x.size(); ++j) {
      const real dx = p.x[i] - p.x[j], dy = p.y[i] - p.y[j], dz = p.z[i] - p.z[j];
      if (j != i && dx * dx + dy * dy + dz * dz < h2) expected.push_back(static_cast<std::uint32_t>(j));
    }
    std::vector<std::uint32_t> got(grid.neighbors(i), grid.neighbors(i) + grid.count(i));
    std::sort(got.begin(), got.end());
    ASSERT_EQ(got, expected) << "particle " << i << " at " << threads << " thread(s)";
    pairs += expected.size();
  }
  EXPECT_GT(pairs, 0u);  // the set must exercise the lists
}

Domain unit_box() {
  Domain d;
  for (int a = 0; a < 3; ++a) d.lo[a] = 0, d.hi[a] = 1;
  return d;
}

}  // namespace

class GridThreads : public ::testing::TestWithParam<int> {
 protected:
  void TearDown() override { omp_set_num_threads(1); }
};

TEST_P(GridThreads, RandomParticles) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(0, 1);
  Cloud p;
  for (int i = 0; i < 3000; ++i) p.add(u(rng), u(rng), u(rng));
  expect_matches_brute_force(p, unit_box(), 0.07, GetParam());
}

TEST_P(GridThreads, EveryParticleInOneCell) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(0.50, 0.52);
  Cloud p;
  for (int i = 0; i < 800; ++i) p.add(u(rng), u(rng), u(rng));
  expect_matches_brute_force(p, unit_box(), 0.1, GetParam());
}

TEST_P(GridThreads, ParticlesOnCellAndDomainFaces) {
  // A lattice whose spacing is the cell size: every particle on cell faces, many on the
  // domain faces, and pairs at exactly distance h (which are not neighbours).
  Cloud p;
  const double h = 0.1;
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 10; ++j)
      for (int k = 0; k <= 3; ++k) p.add(i * h, j * h, k * h);
  for (int i = 0; i < 50; ++i) p.add(0.0, 0.02 * i, 1.0);  // hugging faces and an edge
  expect_matches_brute_force(p, unit_box(), h, GetParam());
}

TEST_P(GridThreads, PredictedPositionsOutsideTheBox) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.2, 1.2);
  Cloud p;
  for (int i = 0; i < 2000; ++i) p.add(u(rng), u(rng), u(rng));
  expect_matches_brute_force(p, unit_box(), 0.08, GetParam());
}

INSTANTIATE_TEST_SUITE_P(OneAndTwoThreads, GridThreads, ::testing::Values(1, 2));

TEST(NeighborGrid, SameListsInTheSameOrderAtAnyThreadCount) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(0, 1);
  Cloud p;
  for (int i = 0; i < 5000; ++i) p.add(u(rng), u(rng), u(rng));
  std::vector<std::vector<std::uint32_t>> lists[2];
  for (int t : {1, 2}) {
    omp_set_num_threads(t);
    NeighborGrid grid;
    grid.bin(p.x.data(), p.y.data(), p.z.data(), p.x.size(), unit_box(), 0.06);
    grid.build_lists(p.x.data(), p.y.data(), p.z.data(), 0.06);
    for (std::size_t i = 0; i < p.x.size(); ++i)
      lists[t - 1].emplace_back(grid.neighbors(i), grid.neighbors(i) + grid.count(i));
  }
  omp_set_num_threads(1);
  EXPECT_EQ(lists[0], lists[1]);
}

// The lists of a build that follows another: in one pass when the particles moved little
// (each block's lists fit the room the last build's sizes give it), in two when they crowded
// together (more neighbours than the room); either way the lists of a grid built afresh, in
// the same order, at 1 and 2 threads.
TEST(NeighborGrid, ARebuildGivesTheListsOfAFreshGrid) {
  for (int t : {1, 2}) {
    omp_set_num_threads(t);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0, 1), jitter(-0.005, 0.005);
    Cloud p;
    for (int i = 0; i < 6000; ++i) p.add(u(rng), u(rng), u(rng));
    const double h = 0.06;
    NeighborGrid grid;
    grid.bin(p.x.data(), p.y.data(), p.z.data(), p.x.size(), unit_box(), h);
    grid.build_lists(p.x.data(), p.y.data(), p.z.data(), h);
    EXPECT_FALSE(grid.built_in_one_pass()) << "the first build has no sizes to go by";
    for (const char* change : {"moved a little", "crowded together"}) {
      for (std::size_t i = 0; i < p.x.size(); ++i) {
        if (change[0] == 'm') {
          p.x[i] = std::clamp(p.x[i] + real(jitter(rng)), real(0), real(1));
          p.y[i] = std::clamp(p.y[i] + real(jitter(rng)), real(0), real(1));
          p.z[i] = std::clamp(p.z[i] + real(jitter(rng)), real(0), real(1));
        } else {
          p.x[i] *= real(0.6), p.y[i] *= real(0.6), p.z[i] *= real(0.6);  // 4.6 times the neighbours
        }
      }
      grid.bin(p.x.data(), p.y.data(), p.z.data(), p.x.size(), unit_box(), h);
      grid.build_lists(p.x.data(), p.y.data(), p.z.data(), h);
      EXPECT_EQ(grid.built_in_one_pass(), change[0] == 'm') << change;
      NeighborGrid fresh;
      fresh.bin(p.x.data(), p.y.data(), p.z.data(), p.x.size(), unit_box(), h);
      fresh.build_lists(p.x.data(), p.y.data(), p.z.data(), h);
      for (std::size_t i = 0; i < p.x.size(); ++i)
        ASSERT_EQ(std::vector<std::uint32_t>(grid.neighbors(i), grid.neighbors(i) + grid.count(i)),
                  std::vector<std::uint32_t>(fresh.neighbors(i), fresh.neighbors(i) + fresh.count(i)))
            << "particle " << i << ", " << change << ", " << t << " thread(s)";
      EXPECT_EQ(grid.mean_neighbors(), fresh.mean_neighbors());
      expect_matches_brute_force(p, unit_box(), h, t);
    }
  }
  omp_set_num_threads(1);
}

// Ordered by id within each cell, a particle's list (as ids) is the same whatever order the
// particles sit in memory: it depends on positions and ids only (issue 11).
TEST(NeighborGrid, ListsInIdsDoNotDependOnMemoryOrder) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  Cloud by_id;
  for (int i = 0; i < 4000; ++i) by_id.add(u(rng), u(rng), u(rng));
  std::vector<std::uint32_t> order(by_id.x.size());  // memory slot k holds particle id order[k]
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = static_cast<std::uint32_t>(k);
  std::vector<std::vector<std::int64_t>> lists[2];  // per id, its neighbours' ids in list order
  for (int pass : {0, 1}) {
    if (pass == 1) std::shuffle(order.begin(), order.end(), rng);
    Cloud p;
    std::vector<std::int64_t> ids;
    for (std::uint32_t id : order) {
      p.add(by_id.x[id], by_id.y[id], by_id.z[id]);
      ids.push_back(id);
    }
    NeighborGrid grid;
    grid.bin(p.x.data(), p.y.data(), p.z.data(), p.x.size(), unit_box(), 0.07);
    grid.order_cells_by(ids.data());
    grid.build_lists(p.x.data(), p.y.data(), p.z.data(), 0.07);
    lists[pass].resize(order.size());
    for (std::size_t i = 0; i < order.size(); ++i)
      for (std::uint32_t k = 0; k < grid.count(i); ++k) lists[pass][order[i]].push_back(ids[grid.neighbors(i)[k]]);
  }
  EXPECT_EQ(lists[0], lists[1]);
  std::size_t pairs = 0;
  for (const auto& l : lists[0]) pairs += l.size();
  EXPECT_GT(pairs, 4000u);  // the premise: enough pairs that the lists are exercised
}

TEST(NeighborGrid, CellCountIsCappedInAHugeBox) {
  Domain d;
  for (int a = 0; a < 3; ++a) d.lo[a] = 0, d.hi[a] = 1000;  // (1000 / 0.01)^3 = 1e15 cells uncapped
  Cloud p;
  for (int i = 0; i < 100; ++i) p.add(500 + 0.004 * i, 500, 500);
  NeighborGrid grid;
  grid.bin(p.x.data(), p.y.data(), p.z.data(), p.x.size(), d, 0.01);
  EXPECT_LE(grid.cell_count(), NeighborGrid::max_cells());
  expect_matches_brute_force(p, d, 0.01, 2);
  omp_set_num_threads(1);
}

// What a rank of a distributed run does (engine/distributed/decomposition.hpp): it bins its
// own particles (those of a box of cells) and the ghosts within one cell of them, over just
// those cells of the whole domain's grid, and lists its own particles' neighbours. The lists,
// as ids, must be those of the whole set: same neighbours, same order. Particles outside the
// domain (clamped into its edge cells) are included.
TEST(NeighborGrid, ABoxOfCellsListsAsTheWholeGridDoes) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.02, 1.02);
  Cloud all;
  std::vector<std::int64_t> all_ids;
  for (int i = 0; i < 6000; ++i) {
    all.add(u(rng), u(rng), u(rng));
    all_ids.push_back(5999 - i);  // ids not in memory order
  }
  const double h = 0.07;
  const GridGeometry g = GridGeometry::of(unit_box(), h);
  NeighborGrid whole;
  whole.bin(all.x.data(), all.y.data(), all.z.data(), all.x.size(), g, CellRange::all(g));
  whole.order_cells_by(all_ids.data());
  whole.build_lists(all.x.data(), all.y.data(), all.z.data(), h);
  // Boxes that touch the domain's faces and boxes inside it.
  const CellRange boxes[] = {{{0, 0, 0}, {5, 15, 15}}, {{4, 3, 2}, {9, 8, 7}}, {{10, 0, 7}, {g.dims[0], 6, g.dims[2]}}};
  for (const CellRange& box : boxes) {
    const CellRange reach{{std::max(0L, box.lo[0] - 1), std::max(0L, box.lo[1] - 1), std::max(0L, box.lo[2] - 1)},
                          {std::min(g.dims[0], box.hi[0] + 1), std::min(g.dims[1], box.hi[1] + 1),
                           std::min(g.dims[2], box.hi[2] + 1)}};
    Cloud local;
    std::vector<std::int64_t> ids;
    std::vector<std::size_t> whole_index;
    for (int pass : {0, 1})  // own particles first, then the ghosts
      for (std::size_t i = 0; i < all.x.size(); ++i) {
        const long c[3] = {g.cell_along(0, all.x[i]), g.cell_along(1, all.y[i]), g.cell_along(2, all.z[i])};
        if (pass == 0 ? !box.contains(c) : (box.contains(c) || !reach.contains(c))) continue;
        local.add(all.x[i], all.y[i], all.z[i]);
        ids.push_back(all_ids[i]);
        whole_index.push_back(i);
      }
    std::size_t own = 0;
    for (std::size_t k = 0; k < ids.size(); ++k) {
      const std::size_t i = whole_index[k];
      const long c[3] = {g.cell_along(0, all.x[i]), g.cell_along(1, all.y[i]), g.cell_along(2, all.z[i])};
      own += box.contains(c);
    }
    NeighborGrid part;
    part.bin(local.x.data(), local.y.data(), local.z.data(), local.x.size(), g, reach);
    part.order_cells_by(ids.data());
    part.build_lists(local.x.data(), local.y.data(), local.z.data(), h, own);
    ASSERT_EQ(part.particle_count(), own);
    ASSERT_GT(own, 50u);
    std::size_t pairs = 0;
    for (std::size_t k = 0; k < own; ++k) {
      const std::size_t i = whole_index[k];
      std::vector<std::int64_t> expected, got;
      for (std::uint32_t m = 0; m < whole.count(i); ++m) expected.push_back(all_ids[whole.neighbors(i)[m]]);
      for (std::uint32_t m = 0; m < part.count(k); ++m) got.push_back(ids[part.neighbors(k)[m]]);
      ASSERT_EQ(got, expected) << "particle id " << ids[k];
      pairs += got.size();
    }
    EXPECT_GT(pairs, own);
  }
}

// The pieces of a distributed run that one process can check (the runs themselves at 2 and 3
// ranks are tests/mpi/run.py's): the exact selection behind percentiles, and particles that
// carry their ids and fields through erase, append and ghosts.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/core/particles.hpp"
#include "engine/distributed/selection.hpp"

using namespace pbf;

// The bisection over the values' bits (what the ranks do together, here with one) selects what
// sorting selects, for negative and positive values, both zeros, repeats and extremes.
TEST(Selection, BisectionOverBitsSelectsAsSortingDoes) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-5, 5);
  std::vector<real> values;
  for (int i = 0; i < 997; ++i) values.push_back(real(u(rng)));
  for (real v : {real(0), real(-0.0), real(1), real(1), real(-1e30), real(1e30), real(1e-40), real(-1e-40)})
    values.push_back(v);
  std::vector<real> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t k : {std::size_t(0), std::size_t(1), std::size_t(500), sorted.size() - 2, sorted.size() - 1}) {
    std::vector<real> copy = values;
    const real got = nth_smallest(copy, k, true);
    EXPECT_TRUE(got == sorted[k]) << "k = " << k << ": " << got << " against " << sorted[k];
    copy = values;
    EXPECT_TRUE(nth_smallest(copy, k, false) == sorted[k]);
  }
  std::vector<real> few = {1, 2};
  EXPECT_THROW(nth_smallest(few, 2, true), Error);
}

// A rank's particles: erase keeps the others' order and ids, append takes ids, and ghosts sit
// after them in every field without counting as its own.
TEST(DistributedParticles, EraseAppendAndGhostsKeepIdsAndFields) {
  Particles P;
  for (int i = 0; i < 5; ++i) {
    const real x[3] = {real(i), 0, 0}, v[3] = {0, real(10 * i), 0};
    P.add(x, v, 1);
  }
  const FieldId extra = P.declare({"extra", 1, "", true});
  for (int i = 0; i < 5; ++i) P.data(extra)[i] = real(100 + i);
  P.erase({0, 1, 0, 1, 0});
  ASSERT_EQ(P.size(), 3u);
  EXPECT_EQ(P.ids()[0], 0);
  EXPECT_EQ(P.ids()[1], 2);
  EXPECT_EQ(P.ids()[2], 4);
  EXPECT_EQ(P.data(extra)[1], real(102));
  EXPECT_EQ(P.vy()[2], real(40));
  const std::int64_t more[] = {7, 9};
  P.append(more);
  EXPECT_EQ(P.size(), 5u);
  EXPECT_EQ(P.ids()[4], 9);
  EXPECT_EQ(P.x()[3], real(0));  // zeroed
  const std::int64_t ghost_ids[] = {11};
  const std::size_t first = P.add_ghosts(ghost_ids);
  EXPECT_EQ(first, 5u);
  EXPECT_EQ(P.size(), 5u);
  EXPECT_EQ(P.size_with_ghosts(), 6u);
  P.data(extra)[first] = 3;  // every field has room for the ghost
  EXPECT_THROW(P.erase(std::vector<char>(5, 0)), Error);  // not with ghosts there
  P.drop_ghosts();
  EXPECT_EQ(P.size_with_ghosts(), 5u);
  EXPECT_EQ(P.next_id(), 5);  // ids of particles created later follow those ever created
}

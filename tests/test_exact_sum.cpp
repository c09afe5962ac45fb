// ExactSum and deterministic_sum: the exact sum of doubles, rounded once, in any order.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "engine/core/exact_sum.hpp"
#include "engine/core/parallel.hpp"

namespace {

using pbf::ExactSum;

double exact(const std::vector<double>& values) {
  ExactSum s;
  for (double v : values) s.add(v);
  return s.value();
}

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

// Values over 80 orders of magnitude, both signs: a plain sum of them depends on the order.
std::vector<double> wide_values(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> mantissa(0.0, 1.0);
  std::uniform_real_distribution<double> exponent(-40.0, 40.0);
  std::vector<double> v(n);
  for (auto& x : v) x = mantissa(rng) * std::pow(10.0, exponent(rng));
  return v;
}

}  // namespace

// What floating-point addition loses, the exact sum keeps: each result is the exact sum of
// the doubles given, rounded to the nearest double (ties to even).
TEST(ExactSum, IsTheExactSumRoundedOnce) {
  EXPECT_EQ(exact({1e100, 1.0, -1e100}), 1.0);  // a plain sum gives 0
  // Ten copies of the double nearest 0.1 sum to 1 + 5.55e-17, nearest double 1 (a plain sum:
  // 0.9999999999999999).
  EXPECT_EQ(exact(std::vector<double>(10, 0.1)), 1.0);
  const double ulp_half = std::ldexp(1.0, -53);
  EXPECT_EQ(exact({1.0, ulp_half}), 1.0);                                      // a tie: to even
  EXPECT_EQ(exact({1.0, ulp_half, std::ldexp(1.0, -200)}), 1.0 + 2 * ulp_half);  // past the tie
  EXPECT_EQ(exact({-5.5, 2.25}), -3.25);
  EXPECT_EQ(exact({std::ldexp(1.0, -1074), std::ldexp(1.0, -1074), std::ldexp(1.0, -1074)}),
            3 * std::ldexp(1.0, -1074));  // subnormals
  EXPECT_EQ(exact({std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(), 2.0}), 2.0);
  EXPECT_EQ(exact({std::numeric_limits<double>::max(), std::numeric_limits<double>::max()}),
            std::numeric_limits<double>::infinity());  // beyond the doubles, as a plain sum
  EXPECT_EQ(exact({}), 0.0);
  EXPECT_EQ(exact({3.0, -3.0}), 0.0);
}

TEST(ExactSum, InfinitiesAndNansAsAPlainSum) {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(exact({1.0, inf}), inf);
  EXPECT_EQ(exact({1.0, -inf}), -inf);
  EXPECT_TRUE(std::isnan(exact({inf, -inf})));
  EXPECT_TRUE(std::isnan(exact({1.0, nan, 2.0})));
}

// The same values in another order, split among accumulators merged in another grouping, or
// passed on as integer words (as MPI will): the same bits. A plain sum of the same values
// differs between the orders (checked, so that the test means something).
TEST(ExactSum, SameBitsInAnyOrderAndGrouping) {
  auto values = wide_values(100000, 7);
  const double reference = exact(values);
  double plain_first = 0, plain_second = 0;
  for (double v : values) plain_first += v;
  std::mt19937_64 rng(11);
  std::shuffle(values.begin(), values.end(), rng);
  for (double v : values) plain_second += v;
  EXPECT_NE(bits(plain_first), bits(plain_second));
  EXPECT_EQ(bits(exact(values)), bits(reference));

  ExactSum a, b, c;
  for (std::size_t i = 0; i < values.size(); ++i) (i % 3 == 0 ? a : i % 3 == 1 ? b : c).add(values[i]);
  ExactSum ab = a, bc = b;
  ab.merge(b);
  ab.merge(c);
  bc.merge(c);
  bc.merge(a);
  EXPECT_EQ(bits(ab.value()), bits(reference));
  EXPECT_EQ(bits(bc.value()), bits(reference));

  auto words = a.words();
  const auto wb = b.words(), wc = c.words();
  for (std::size_t k = 0; k < words.size(); ++k) words[k] += wb[k] + wc[k];
  ExactSum from_words;
  from_words.set_words(words);
  EXPECT_EQ(bits(from_words.value()), bits(reference));
  from_words.add(1e30);
  from_words.add(-1e30);  // and it goes on adding after
  EXPECT_EQ(bits(from_words.value()), bits(reference));
}

// deterministic_sum: the same bits at any thread count and in any order of the terms.
TEST(DeterministicSum, SameBitsAtAnyThreadCountAndOrder) {
  auto values = wide_values(50000, 3);
  const double reference = exact(values);
  const int before = omp_get_max_threads();
  for (int threads : {1, 2, 3, 7}) {
    omp_set_num_threads(threads);
    EXPECT_EQ(bits(pbf::deterministic_sum(values.size(), [&](std::size_t i) { return values[i]; })), bits(reference))
        << threads << " threads";
  }
  std::reverse(values.begin(), values.end());
  EXPECT_EQ(bits(pbf::deterministic_sum(values.size(), [&](std::size_t i) { return values[i]; })), bits(reference));
  omp_set_num_threads(before);
}

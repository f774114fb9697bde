// The portable random helpers: ranges, moments over many draws, reproducibility.

#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "kautham/core/Random.h"

namespace kautham::core {
namespace {

constexpr int kDraws = 100000;

TEST(Random, Uniform01IsInsideTheOpenIntervalWithMeanAndVarianceOfTheUniform) {
  std::mt19937_64 rng(7);
  double sum = 0.0, squares = 0.0, low = 1.0, high = 0.0;
  for (int i = 0; i < kDraws; ++i) {
    const double u = uniform01(rng);
    ASSERT_GT(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    squares += u * u;
    low = std::min(low, u);
    high = std::max(high, u);
  }
  const double mean = sum / kDraws;
  // The mean of 1e5 uniforms has a standard error of 0.29 / 316 = 0.0009.
  EXPECT_NEAR(mean, 0.5, 0.005);
  EXPECT_NEAR(squares / kDraws - mean * mean, 1.0 / 12.0, 0.003);
  EXPECT_LT(low, 1e-3);  // the whole interval is covered
  EXPECT_GT(high, 1.0 - 1e-3);
}

TEST(Random, Uniform01IsTheTop53BitsOfOneRawDraw) {
  std::mt19937_64 a(11), b(11);
  for (int i = 0; i < 100; ++i) {
    const std::uint64_t raw = b();
    EXPECT_EQ(uniform01(a), (static_cast<double>(raw >> 11) + 0.5) / 9007199254740992.0);
  }
  EXPECT_EQ(a(), b());  // one raw draw each: still in step
}

TEST(Random, StandardNormalHasMeanZeroAndVarianceOne) {
  std::mt19937_64 rng(2024);
  double sum = 0.0, squares = 0.0, fourth = 0.0;
  int beyondTwo = 0;
  for (int i = 0; i < kDraws; ++i) {
    const double x = standardNormal(rng);
    ASSERT_TRUE(std::isfinite(x));
    sum += x;
    squares += x * x;
    fourth += x * x * x * x;
    beyondTwo += std::abs(x) > 1.959963985 ? 1 : 0;
  }
  // Standard errors over 1e5 draws: mean 0.0032, variance 0.0045; bounds at about 4.5 of them.
  EXPECT_NEAR(sum / kDraws, 0.0, 0.015);
  EXPECT_NEAR(squares / kDraws, 1.0, 0.02);
  EXPECT_NEAR(fourth / kDraws, 3.0, 0.15);  // a normal's kurtosis, not just any unit variance
  EXPECT_NEAR(beyondTwo / double(kDraws), 0.05, 0.004);
}

TEST(Random, StandardNormalConsumesExactlyTwoRawDraws) {
  std::mt19937_64 a(3), b(3);
  for (int i = 0; i < 10; ++i) {
    standardNormal(a);
    b.discard(2);
    EXPECT_EQ(a(), b());
  }
}

TEST(Random, SameSeedSameNumbersOtherSeedOtherNumbers) {
  std::mt19937_64 a(99), b(99), c(100);
  std::vector<double> first, second, other;
  for (int i = 0; i < 1000; ++i) {
    first.push_back(standardNormal(a));
    second.push_back(standardNormal(b));
    other.push_back(standardNormal(c));
  }
  EXPECT_EQ(first, second);
  EXPECT_NE(first, other);
}

TEST(Random, RunSeedsDependOnSeedAndIndexOnly) {
  std::set<std::uint64_t> seeds;
  for (std::uint64_t seed : {0u, 1u, 2u})
    for (std::uint64_t run = 0; run < 1000; ++run) seeds.insert(runSeed(seed, run));
  EXPECT_EQ(seeds.size(), 3000u);  // no two streams start alike
  EXPECT_EQ(runSeed(1, 5), runSeed(1, 5));
  EXPECT_NE(runSeed(1, 5), runSeed(5, 1));
}

}  // namespace
}  // namespace kautham::core

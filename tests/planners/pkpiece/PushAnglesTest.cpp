// The angles p-KPIECE's trees push each object at: drawn for the tree alone, or learned from
// how near the trees before each generation got.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "kautham/planners/pkpiece/PushAngles.h"

namespace kautham::planners {
namespace {

constexpr std::size_t kBodies = 6;
constexpr std::size_t kCan = 3;  // the object whose angle decides how near a tree gets

/// The angle every tree up to `trees` pushes `body` at.
std::vector<double> anglesOf(PushAngles& angles, std::uint64_t trees, std::size_t body) {
  std::vector<double> out;
  for (std::uint64_t t = 0; t < trees; ++t) {
    angles.setTree(t);
    out.push_back(angles.angle(body));
  }
  return out;
}

TEST(PushAnglesTest, TreesBeforeTheFirstTurnedOnePushStraightAndTheRestWithinTheSpread) {
  PushAngles angles({0.8, 3, 0}, kBodies);
  const std::vector<double> can = anglesOf(angles, 40, kCan);
  for (std::uint64_t t = 0; t < 3; ++t) EXPECT_EQ(can[t], 0.0) << "tree " << t;
  double lowest = 0.0, highest = 0.0;
  for (std::uint64_t t = 3; t < 40; ++t) {
    EXPECT_LE(std::abs(can[t]), 0.8) << "tree " << t;
    lowest = std::min(lowest, can[t]);
    highest = std::max(highest, can[t]);
    EXPECT_EQ(angles.treesBefore(t), 0u);  // nothing to wait for
  }
  EXPECT_LT(lowest, -0.4);  // both ways, and far
  EXPECT_GT(highest, 0.4);
  // A tree's angle depends on the seed, the tree and the object alone.
  PushAngles again({0.8, 3, 0}, kBodies);
  EXPECT_EQ(anglesOf(again, 40, kCan), can);
  EXPECT_NE(anglesOf(again, 40, kCan + 1), can);
}

TEST(PushAnglesTest, AnotherSeedDrawsOtherAnglesForTheSameTree) {
  // Runs with other seeds must sample other angles: with one sequence for every seed, a benchmark
  // over seeds would measure that sequence's luck (benchmarks.md, session 63).
  PushAngles one({0.8, 1, 0, 1}, kBodies);
  PushAngles two({0.8, 1, 0, 2}, kBodies);
  PushAngles oneAgain({0.8, 1, 0, 1}, kBodies);
  const std::vector<double> can = anglesOf(one, 30, kCan);
  EXPECT_EQ(anglesOf(oneAgain, 30, kCan), can);
  const std::vector<double> other = anglesOf(two, 30, kCan);
  EXPECT_EQ(other[0], 0.0);  // the first tree pushes straight under any seed
  int differ = 0;
  for (std::uint64_t t = 1; t < 30; ++t) differ += other[t] != can[t];
  EXPECT_EQ(differ, 29);
}

TEST(PushAnglesTest, TheFirstGenerationDrawsAsTreesWithoutLearning) {
  PushAngles drawn({0.8, 3, 0}, kBodies);
  PushAngles learned({0.8, 3, 8}, kBodies);
  for (std::size_t body = 0; body < kBodies; ++body)
    EXPECT_EQ(anglesOf(learned, 11, body), anglesOf(drawn, 11, body)) << "body " << body;
  EXPECT_EQ(learned.treesBefore(10), 0u);
  EXPECT_EQ(learned.treesBefore(11), 11u);  // the second generation: trees 11-18
  EXPECT_EQ(learned.treesBefore(18), 11u);
  EXPECT_EQ(learned.treesBefore(19), 19u);
}

TEST(PushAnglesTest, ALaterGenerationCannotStartBeforeTheTreesItLearnsFrom) {
  PushAngles angles({0.8, 3, 8}, kBodies);
  for (std::uint64_t t = 0; t < 10; ++t) angles.record(t, 1.0);  // tree 10 missing
  EXPECT_THROW(angles.setTree(11), std::logic_error);
  angles.record(10, 1.0);
  EXPECT_NO_THROW(angles.setTree(11));
}

TEST(PushAnglesTest, LaterGenerationsPushNearTheAnglesOfTheNearestTrees) {
  // A tree gets nearer the nearer it pushes the can at 0.5 rad, whatever its other angles.
  constexpr double kBest = 0.5;
  PushAngles angles({0.8, 1, 8}, kBodies);
  std::vector<double> error;  // of each generation's draws for the can, from kBest
  for (std::uint64_t generation = 0; generation < 6; ++generation) {
    double sum = 0.0;
    for (std::uint64_t i = 0; i < 8; ++i) {
      const std::uint64_t tree = 1 + 8 * generation + i;
      angles.setTree(tree);
      const double off = std::abs(angles.angle(kCan) - kBest);
      angles.record(tree, off);
      sum += off;
    }
    error.push_back(sum / 8.0);
  }
  // The uniform first generation is off by about 0.4 rad on average; the learned ones close in.
  EXPECT_GT(error.front(), 0.2);
  EXPECT_LT(error.back(), 0.1);
  // An object whose angle does not matter keeps being pushed at a spread of angles.
  std::vector<double> other;
  for (std::uint64_t tree = 41; tree < 49; ++tree) {
    angles.setTree(tree);
    other.push_back(angles.angle(kCan + 1));
  }
  const auto [lo, hi] = std::minmax_element(other.begin(), other.end());
  EXPECT_GT(*hi - *lo, 0.1);
}

TEST(PushAnglesTest, ForgettingStartsTheLearningAgain) {
  // Generations of four from tree 1: the second learns from the nearest three of trees 1-4.
  PushAngles angles({0.8, 1, 4}, kBodies);
  PushAngles fresh({0.8, 1, 4}, kBodies);
  const auto recordFurthest = [](PushAngles& a, std::uint64_t furthest) {
    for (std::uint64_t t = 0; t < 5; ++t) a.record(t, t == furthest ? 9.0 : 1.0);
  };
  recordFurthest(angles, 1);
  angles.setTree(5);
  const double learned = angles.angle(kCan);
  angles.forget();
  EXPECT_THROW(angles.setTree(5), std::logic_error);  // nothing recorded now
  recordFurthest(angles, 4);
  recordFurthest(fresh, 4);
  angles.setTree(5);
  fresh.setTree(5);
  EXPECT_EQ(angles.angle(kCan), fresh.angle(kCan));
  EXPECT_NE(angles.angle(kCan), learned);
}

}  // namespace
}  // namespace kautham::planners

// How a search takes in the results of trees grown in parallel: in index order, whatever order
// they finish in. Tree 0 is made the slowest, so that tree 1 finishes first; every assertion
// holds whatever the timing, which only decides whether the waiting is exercised.

#include <chrono>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "kautham/planners/pkpiece/TreesInOrder.h"

namespace kautham::planners {
namespace {

using namespace std::chrono_literals;

/// Byte 0 of a tree's result: 1 when it ends the search (a verified plan). Byte 1: its index.
TreeProcesses::Grow trees(std::vector<unsigned char> ending) {
  return [ending](std::size_t tree, TreeProcesses::LentCores&) -> std::vector<unsigned char> {
    if (tree == 0) std::this_thread::sleep_for(300ms);  // the slowest to finish
    const unsigned char ends = tree < ending.size() ? ending[tree] : 0;
    return {ends, static_cast<unsigned char>(tree)};
  };
}

struct Taken {
  TreesTaken counts;
  std::vector<int> order;                  ///< the trees taken in, in the order they were
  std::vector<TreeOrder::Result> results;  ///< their results, in the same order
};

Taken takeIn(TreeProcesses& processes) {
  Taken taken;
  TreeOrder order;
  order.ends = [](const TreeOrder::Result& r) { return r.at(0) == 1; };
  order.takeIn = [&taken](const TreeOrder::Result& r) {
    taken.order.push_back(r.at(1));
    taken.results.push_back(r);
    return r.at(0) == 1;
  };
  const auto guard = std::chrono::steady_clock::now() + 60s;  // against a hang, not timing
  order.stop = [guard] { return std::chrono::steady_clock::now() > guard; };
  taken.counts = takeTreesInOrder(processes, order);
  return taken;
}

TEST(TreesInOrderTest, ALaterTreesPlanWaitsForAnEarlierTreeThatEndsTheSearch) {
  // Trees 0 and 1 both end with a plan; tree 1 finishes first. The plan is tree 0's, and tree
  // 1's result is never taken in.
  TreeProcesses processes(2, trees({1, 1}));
  const Taken taken = takeIn(processes);
  EXPECT_EQ(taken.order, (std::vector<int>{0}));
  EXPECT_EQ(taken.counts.takenIn, 1u);
  EXPECT_EQ(taken.counts.started, 2u);
  EXPECT_TRUE(processes.idle());
}

TEST(TreesInOrderTest, ALaterTreesPlanIsTakenAfterTheEarlierTreesWithout) {
  // Tree 0 ends without a plan, after tree 1 found one: tree 0 is taken in first, then tree 1
  // ends the search; no tree after tree 1 starts.
  TreeProcesses processes(2, trees({0, 1}));
  const Taken taken = takeIn(processes);
  EXPECT_EQ(taken.order, (std::vector<int>{0, 1}));
  EXPECT_EQ(taken.counts.started, 2u);
}

TEST(TreesInOrderTest, OneAtATimeTheTreesAreTakenInTheSameOrder) {
  // Trees 0-2 without a plan, tree 3 with one: one process or three, the same trees taken in.
  for (unsigned processes : {1u, 3u}) {
    TreeProcesses pool(processes, trees({0, 0, 0, 1}));
    const Taken taken = takeIn(pool);
    EXPECT_EQ(taken.order, (std::vector<int>{0, 1, 2, 3})) << processes << " at once";
    EXPECT_LE(taken.counts.started, 3u + processes) << processes << " at once";
  }
}

/// Tree 0 grows until `wanted` cores are lent to it (at most 30 s); tree 1 ends the search at
/// once; any later tree grows for ever. Byte 2 of a result: the cores lent to that tree.
TreeProcesses::Grow treeZeroWaitsForCores(unsigned wanted) {
  return [wanted](std::size_t tree, TreeProcesses::LentCores& lent) -> std::vector<unsigned char> {
    if (tree > 1)
      for (;;) std::this_thread::sleep_for(1s);
    unsigned cores = 0;
    const auto guard = std::chrono::steady_clock::now() + 30s;
    if (tree == 0)
      while (cores < wanted && std::chrono::steady_clock::now() < guard) {
        cores += lent.collect();
        std::this_thread::sleep_for(5ms);
      }
    return {static_cast<unsigned char>(tree == 1 ? 1 : 0), static_cast<unsigned char>(tree),
            static_cast<unsigned char>(cores)};
  };
}

TEST(TreesInOrderTest, ATreeHoldingUpTheEndIsLentTheCoreLeftIdle) {
  // Tree 1 ends the search while tree 0 grows: tree 1's core is lent to tree 0, which without
  // it would grow on for 30 s. Tree 0 is then taken in, and tree 1 ends the search.
  TreeProcesses processes(2, treeZeroWaitsForCores(1));
  const Taken taken = takeIn(processes);
  ASSERT_EQ(taken.order, (std::vector<int>{0, 1}));
  EXPECT_EQ(taken.results[0].at(2), 1);  // one core lent to tree 0
}

TEST(TreesInOrderTest, TreesAfterTheOneThatEndsTheSearchStopAndLendTheirCores) {
  // Three at once: tree 2 would grow for ever, but once tree 1 ends the search it is stopped,
  // and its core and tree 1's are lent to tree 0.
  TreeProcesses processes(3, treeZeroWaitsForCores(2));
  const Taken taken = takeIn(processes);
  EXPECT_EQ(taken.counts.started, 3u);
  ASSERT_EQ(taken.order, (std::vector<int>{0, 1}));
  EXPECT_EQ(taken.results[0].at(2), 2);  // two cores lent to tree 0
  EXPECT_TRUE(processes.idle());
}

TEST(TreesInOrderTest, ATreeThatLearnsFromEarlierOnesStartsOnceTheyAreTakenIn) {
  // Trees 2 and 3 learn from trees 0 and 1 (takenInBefore 2): with two processes, tree 2 would
  // start as soon as tree 1 finishes, while tree 0 still grows. Each tree's process is a copy of
  // the search as it started, so a tree's result can say how many trees were taken in by then.
  std::vector<int> takenOrder;
  TreeProcesses processes(
      2, [&takenOrder](std::size_t tree, TreeProcesses::LentCores&) -> std::vector<unsigned char> {
        if (tree == 0) std::this_thread::sleep_for(300ms);  // tree 1 finishes first
        return {static_cast<unsigned char>(tree == 3 ? 1 : 0), static_cast<unsigned char>(tree),
                static_cast<unsigned char>(takenOrder.size())};
      });
  std::vector<TreeOrder::Result> results;
  TreeOrder order;
  order.ends = [](const TreeOrder::Result& r) { return r.at(0) == 1; };
  order.takeIn = [&](const TreeOrder::Result& r) {
    takenOrder.push_back(r.at(1));
    results.push_back(r);
    return r.at(0) == 1;
  };
  order.takenInBefore = [](std::size_t tree) -> std::size_t { return tree >= 2 ? 2 : 0; };
  const auto guard = std::chrono::steady_clock::now() + 60s;  // against a hang, not timing
  order.stop = [guard] { return std::chrono::steady_clock::now() > guard; };
  takeTreesInOrder(processes, order);
  ASSERT_EQ(takenOrder, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(results[0].at(2), 0);  // trees 0 and 1 started at once
  EXPECT_EQ(results[1].at(2), 0);
  EXPECT_GE(results[2].at(2), 2);  // trees 2 and 3 after both were taken in
  EXPECT_GE(results[3].at(2), 2);
}

}  // namespace
}  // namespace kautham::planners

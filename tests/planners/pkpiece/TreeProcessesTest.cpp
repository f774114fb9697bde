// The processes p-KPIECE grows its trees in (parallel_trees): each tree's result comes back
// with its index; a process that dies without its result is an error naming the tree, never a
// hang; the processes still growing are killed and reaped when the pool goes.

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "kautham/planners/pkpiece/TreeProcesses.h"

namespace kautham::planners {
namespace {

using namespace std::chrono_literals;

/// Results until `count` trees finished (with a generous guard against a hang).
std::map<std::size_t, std::vector<unsigned char>> collect(TreeProcesses& trees, std::size_t count) {
  std::map<std::size_t, std::vector<unsigned char>> results;
  const auto guard = std::chrono::steady_clock::now() + 60s;
  while (results.size() < count && std::chrono::steady_clock::now() < guard)
    if (auto done = trees.wait(100ms)) results.emplace(done->tree, std::move(done->result));
  return results;
}

TEST(TreeProcessesTest, EachTreesResultComesBackWithItsIndex) {
  // Tree k answers k + 1 bytes of value k, from a process of its own: its pid differs from
  // this one's, so the work really ran elsewhere.
  const pid_t self = ::getpid();
  TreeProcesses trees(2, [self](std::size_t tree, TreeProcesses::LentCores&) {
    std::vector<unsigned char> bytes(tree + 1, static_cast<unsigned char>(tree));
    bytes.push_back(::getpid() != self ? 1 : 0);
    return bytes;
  });
  std::size_t next = 0;
  std::map<std::size_t, std::vector<unsigned char>> results;
  while (results.size() < 5) {
    while (!trees.full() && next < 5) trees.start(next++);
    EXPECT_LE(next - results.size(), 2u);  // never more than two at once
    auto done = collect(trees, 1);
    ASSERT_FALSE(done.empty()) << "no tree finished within a minute";
    for (auto& [tree, bytes] : done) results.emplace(tree, std::move(bytes));
  }
  for (std::size_t tree = 0; tree < 5; ++tree) {
    std::vector<unsigned char> expected(tree + 1, static_cast<unsigned char>(tree));
    expected.push_back(1);
    EXPECT_EQ(results.at(tree), expected) << tree;
  }
  EXPECT_TRUE(trees.idle());
}

TEST(TreeProcessesTest, AProcessThatDiesWithoutItsResultIsAnErrorNamingItsTree) {
  TreeProcesses trees(
      1, [](std::size_t tree, TreeProcesses::LentCores&) -> std::vector<unsigned char> {
        if (tree == 1) std::abort();
        if (tree == 2) throw std::runtime_error("a broken tree");
        return {1, 2, 3};
      });
  for (std::size_t tree : {1u, 2u}) {
    trees.start(tree);
    try {
      collect(trees, 1);
      ADD_FAILURE() << "tree " << tree << "'s death was not reported";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("tree " + std::to_string(tree)), std::string::npos)
          << e.what();
    }
    EXPECT_TRUE(trees.idle());  // reaped
  }
  trees.start(0);  // the pool goes on
  EXPECT_EQ(collect(trees, 1).at(0), (std::vector<unsigned char>{1, 2, 3}));
}

TEST(TreeProcessesTest, TreesStillGrowingAreKilledWhenThePoolGoes) {
  // Each tree writes its pid where this test reads it, then grows for ever.
  const std::string prefix =
      ::testing::TempDir() + "/tree_process_" + std::to_string(::getpid()) + "_";
  const auto pidFile = [&prefix](std::size_t tree) { return prefix + std::to_string(tree); };
  std::vector<pid_t> pids;
  {
    TreeProcesses trees(
        2, [&pidFile](std::size_t tree, TreeProcesses::LentCores&) -> std::vector<unsigned char> {
          std::ofstream(pidFile(tree)) << ::getpid() << std::endl;
          for (;;) std::this_thread::sleep_for(1s);
        });
    trees.start(0);
    trees.start(1);
    EXPECT_TRUE(trees.full());
    for (std::size_t tree : {0u, 1u}) {
      pid_t pid = 0;
      for (int tries = 0; tries < 600 && pid == 0; ++tries) {
        std::ifstream(pidFile(tree)) >> pid;
        if (pid == 0) std::this_thread::sleep_for(100ms);
      }
      ASSERT_GT(pid, 0) << "tree " << tree << " never started";
      pids.push_back(pid);
    }
    EXPECT_FALSE(trees.wait(50ms));  // neither ends on its own
  }
  for (const pid_t pid : pids) {
    EXPECT_EQ(::kill(pid, 0), -1) << pid << " still exists";  // killed and reaped
    EXPECT_EQ(errno, ESRCH);
  }
  for (std::size_t tree : {0u, 1u}) std::remove(pidFile(tree).c_str());
}

}  // namespace
}  // namespace kautham::planners

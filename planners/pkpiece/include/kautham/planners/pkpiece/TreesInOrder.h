#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <vector>

#include "kautham/planners/pkpiece/TreeProcesses.h"

namespace kautham::planners {

/// How a search takes in the results of trees grown in parallel (`parallel_trees`).
struct TreeOrder {
  using Result = std::vector<unsigned char>;
  /// Whether a result, once taken in, ends the search (a verified plan): no later tree starts.
  std::function<bool(const Result&)> ends;
  /// Takes a result into the search (called in index order); returns ends(result).
  std::function<bool(const Result&)> takeIn;
  /// Whether the search must stop (its termination condition, the time limit).
  std::function<bool()> stop;
  /// How many trees (0, 1, ...) must be taken in before `tree` may start: a tree that learns
  /// from the ones before it waits for them. Unset: none.
  std::function<std::size_t(std::size_t tree)> takenInBefore;
  /// Once stop() holds, how long the trees still growing have to end on their own before they
  /// are killed: they see the time limit themselves, not a condition only this process sees
  /// (Ctrl-C).
  std::chrono::milliseconds grace{2000};
  /// How often stop() is looked at while trees grow.
  std::chrono::milliseconds poll{20};
};

/// What takeTreesInOrder() did.
struct TreesTaken {
  std::size_t started = 0;  ///< trees 0..started-1 were started
  std::size_t takenIn = 0;  ///< results handed to takeIn
};

/// Starts trees 0, 1, 2... as `trees` has room (and each has the trees it needs taken in:
/// `order.takenInBefore`) and hands their results to `order.takeIn` in index
/// order, whatever order they finish in, until one ends the search: tree k's result waits for
/// trees 0..k-1, so a later tree's plan is never taken before an earlier tree's, and the plan does
/// not depend on how many trees grow at once. No tree after one whose result ends the search is
/// started, those growing are stopped, and the cores left idle are lent to the trees before it
/// (TreeProcesses::lendIdleCores). Once `order.stop()` holds, the trees get `order.grace` to end,
/// the rest are killed, and the results in hand are taken in order, those of killed trees passed
/// over.
TreesTaken takeTreesInOrder(TreeProcesses& trees, const TreeOrder& order);

}  // namespace kautham::planners

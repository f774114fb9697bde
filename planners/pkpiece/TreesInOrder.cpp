#include "kautham/planners/pkpiece/TreesInOrder.h"

#include <algorithm>
#include <map>
#include <optional>
#include <utility>

namespace kautham::planners {

TreesTaken takeTreesInOrder(TreeProcesses& trees, const TreeOrder& order) {
  using Clock = std::chrono::steady_clock;
  TreesTaken taken;
  // Results by tree, until every tree before them is taken in.
  std::map<std::size_t, TreeOrder::Result> finished;
  std::optional<std::size_t> firstEnding;  // no tree after it need start
  std::optional<Clock::time_point> killAt;
  bool ended = false;
  while (!ended) {
    if (!order.stop()) {
      while (!trees.full() && (!firstEnding || taken.started < *firstEnding) &&
             (!order.takenInBefore || taken.takenIn >= order.takenInBefore(taken.started)))
        trees.start(taken.started++);
    } else if (!killAt) {
      killAt = Clock::now() + order.grace;
    }
    if (trees.idle() || (killAt && Clock::now() >= *killAt)) break;
    if (std::optional<TreeProcesses::Finished> done = trees.wait(order.poll)) {
      if (order.ends(done->result))
        firstEnding = std::min(done->tree, firstEnding.value_or(done->tree));
      finished.emplace(done->tree, std::move(done->result));
    }
    if (firstEnding && !killAt) {
      // Only the trees before it can still change the plan: the later ones stop, and every
      // core no tree grows on helps those (their work spread over it gives the same results).
      trees.stopAfter(*firstEnding);
      trees.lendIdleCores();
    }
    for (auto it = finished.find(taken.takenIn); it != finished.end() && !ended;
         it = finished.find(taken.takenIn)) {
      ended = order.takeIn(it->second);
      finished.erase(it);
      ++taken.takenIn;
    }
  }
  trees.stopAll();
  // Stopped with trees killed before they answered: those are passed over, and the results in
  // hand are still taken in order (one that ends the search among them ends it).
  for (auto it = finished.begin(); it != finished.end() && !ended; ++it) {
    ended = order.takeIn(it->second);
    ++taken.takenIn;
  }
  return taken;
}

}  // namespace kautham::planners

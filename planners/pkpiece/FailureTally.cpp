#include "kautham/planners/pkpiece/FailureTally.h"

#include <algorithm>

namespace kautham::planners {

void FailureTally::addViolation(physics::Violation violation, std::optional<std::size_t> body) {
  ++counts_[{violation, body}];
  ++total_;
}

void FailureTally::addDisplacement(std::size_t body) {
  ++counts_[{physics::Violation::None, body}];
  ++total_;
}

std::vector<FailureTally::Entry> FailureTally::entries() const {
  std::vector<Entry> result;
  for (const auto& [key, count] : counts_) result.push_back({key.first, key.second, count});
  return result;
}

void FailureTally::add(const Entry& entry) {
  counts_[{entry.violation, entry.body}] += entry.count;
  total_ += entry.count;
}

std::vector<FailureCount> FailureTally::counts(const physics::WorldLayout& layout) const {
  std::vector<FailureCount> result;
  for (const auto& [key, count] : counts_) {
    const auto& [violation, body] = key;
    FailureCount entry;
    entry.reason =
        violation == physics::Violation::None ? "moved more than d" : physics::toString(violation);
    entry.object = body ? layout.bodies[*body].name : "";
    entry.count = count;
    result.push_back(std::move(entry));
  }
  // Most frequent first; the map's order (reason, body) breaks ties, so the list is stable.
  std::stable_sort(result.begin(), result.end(),
                   [](const FailureCount& a, const FailureCount& b) { return a.count > b.count; });
  return result;
}

}  // namespace kautham::planners

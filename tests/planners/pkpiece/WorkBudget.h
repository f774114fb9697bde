#pragma once
// The p-KPIECE tests that plan until a plan is found end their search by the work done, not by
// the clock: a starved machine (a build beside them, a low priority) runs them slower but gives
// the same answer, and a search that has gone wrong still ends, at the same motion every time.

#include <algorithm>
#include <vector>

#include "kautham/planners/PlanRequest.h"

namespace kautham::test {

/// About five times the motions the longest of these searches grows (21 257, in
/// PKpieceTest.CollectsVerifiedPlansFromNewTreesAndReturnsOneOfThem).
inline constexpr const char* kTestMotionBudget = "100000";

/// `overrides` with the motion budget (unless they set their own) and an hour's time limit
/// (unless they set their own), a guard against a hang that the budget always reaches first on
/// any machine that runs the tests.
inline std::vector<planners::ParameterOverride> withWorkBudget(
    std::vector<planners::ParameterOverride> overrides) {
  const auto sets = [&overrides](const char* name) {
    return std::any_of(overrides.begin(), overrides.end(),
                       [name](const auto& set) { return set.first == name; });
  };
  if (!sets("max_motions")) overrides.push_back({"max_motions", kTestMotionBudget});
  if (!sets("time_limit")) overrides.push_back({"time_limit", "3600"});
  return overrides;
}

}  // namespace kautham::test

#pragma once

// A motion of p-KPIECE's tree (PKpiece.cpp grows them; PKpieceTrees.cpp moves a tree's plan
// between processes).

#include <memory>
#include <vector>

#include "kautham/planners/pkpiece/PKpiece.h"

namespace kautham::planners {

struct PKpiece::Motion {
  ompl::base::State* state = nullptr;  ///< the state at the motion's end
  std::vector<double> control;
  unsigned steps = 0;
  Motion* parent = nullptr;
  double belief = 1.0;  ///< b of the candidate it came from
  /// Its particles' b, before executions of rejected plans through it were weighed in
  /// (learnFromExecutions).
  double particleBelief = 1.0;
  /// The particles that judged it: n_p, or fewer when the first certain_after all succeeded.
  /// As many runs are what particleBelief weighs against executions (learnFromExecutions).
  unsigned particleRuns = 0;
  unsigned executionsThrough = 0;  ///< rejected plans' executions that began its candidate
  unsigned executionsPassed = 0;   ///< of those, the ones that got through it
  double pathBelief = 1.0;         ///< product of the candidates' beliefs from the root to here
  std::shared_ptr<const ObjectPoseBelief> poses;
  std::shared_ptr<const RobotSpread> robotSpread;  ///< null: particles start as the state
  unsigned expansion = 0;  ///< the iteration that added it: its pieces share the number
  double goalDistance = 0.0;
  CellData* cell = nullptr;
  bool reachesGoal = false;  ///< ends a plan estimated to succeed often enough (goalConfidence)
  /// With reachesGoal: that estimate, the path belief to its parent times the fraction of its
  /// (confirming) particles that end valid in the goal; once verified (verifyRuns), the
  /// fraction of the plan's sampled executions that succeeded.
  double successEstimate = 0.0;
};

}  // namespace kautham::planners

#include "kautham/planners/pkpiece/ExecutionBelief.h"

namespace kautham::planners {

double beliefAfterExecutions(double particleBelief, unsigned particleRuns, unsigned began,
                             unsigned gotThrough) {
  const double runs = static_cast<double>(particleRuns) + began;
  if (runs <= 0.0) return particleBelief;
  return (particleRuns * particleBelief + gotThrough) / runs;
}

}  // namespace kautham::planners

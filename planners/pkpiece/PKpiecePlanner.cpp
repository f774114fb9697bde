// p-KPIECE's registry entry: the paper's planner, ours, on OMPL's grid (its baseline o-KPIECE,
// OMPL's KPIECE1 with the knowledge rules only, is with the other OMPL planners).

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "kautham/planners/PlannerEntry.h"
#include "kautham/planners/pkpiece/PKpiece.h"

namespace kautham::planners {

namespace {

/// The steered approach aims the gripper `pitch` off the goal's approach: beyond the goal's
/// tolerance it could never end in the goal.
void checkApproachPitch(double pitch, const physics::GoalSpec& goal) {
  if (!goal.approach || std::abs(pitch) <= goal.approachTolerance) return;
  std::ostringstream message;
  message << "approach_pitch " << pitch << " rad is beyond the goal's approach tolerance ("
          << goal.approachTolerance << " rad): the steered approach would end outside the goal; "
          << "use at most " << goal.approachTolerance << " (the dense suite uses 0.2)";
  throw std::invalid_argument(message.str());
}

/// Without particles only the verification judges a plan under uncertainty: with neither, the
/// plan would end the search unjudged, its estimate a nominal 100 %.
void checkSomethingJudges(const PKpieceSettings& settings) {
  if (!settings.uncertainty || settings.particles > 0 || settings.verifyRuns > 0) return;
  throw std::invalid_argument(
      "particles 0 with verify_runs 0: nothing would judge the plan under uncertainty; set "
      "verify_runs > 0 (whole plans verified, 50 by default), particles > 0, or uncertainty 0 "
      "(the paper's pKP)");
}

/// Choosing among several plans, or holding one to a bar, needs each one's measured success:
/// only verification has it.
void checkPlansCanBeCompared(const PKpieceSettings& settings) {
  if (settings.uncertainty && settings.verifyRuns > 0) return;
  if (settings.plans > 1)
    throw std::invalid_argument(
        "plans " + std::to_string(settings.plans) +
        " needs verified plans to choose from: set uncertainty 1 and verify_runs > 0, or plans 1");
  if (settings.aspiration > 0.0) {
    std::ostringstream message;
    message << "aspiration " << settings.aspiration
            << " needs plans' measured success: set uncertainty 1 and verify_runs > 0, or "
               "aspiration 0";
    throw std::invalid_argument(message.str());
  }
}

/// Trees grown at once end the search in their order, one plan from one tree: nothing to
/// collect or compare across them, and no shared budget of motions.
void checkParallelTrees(const PKpieceSettings& settings) {
  if (!settings.parallelTrees) return;
  if (settings.plans > 1 || settings.aspiration > 0.0 || settings.maxMotions > 0)
    throw std::invalid_argument(
        "parallel_trees needs plans 1, aspiration 0 and max_motions 0 (trees grown at once end "
        "the search with the first plan in their order); set parallel_trees 0 for those");
}

PlannerRegistry::Entry pKpiece() {
  return plannerEntry<PKpieceSettings>(
      "p-KPIECE",
      "the paper's planner: keeps the most robust of k candidates, judged by n_p particles "
      "under pose, contact and control uncertainty",
      PKpieceSettings::parameters(),
      [](const PKpieceSettings& settings, physics::PlanningContext& context) {
        PKpieceSettings resolved = settings;
        if (resolved.displacement <= 0.0)
          resolved.displacement = context.problem().interaction.maxDisplacement;
        checkApproachPitch(resolved.approachPitch, context.goal().spec());
        checkSomethingJudges(resolved);
        checkPlansCanBeCompared(resolved);
        checkParallelTrees(resolved);
        return ompl::base::PlannerPtr(std::make_shared<PKpiece>(context, resolved));
      });
}

}  // namespace

void registerPKpiece(PlannerRegistry& registry) { registry.add(pKpiece()); }

}  // namespace kautham::planners

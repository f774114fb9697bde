// The KPIECE family of the paper: p-KPIECE (ours, on OMPL's grid) and o-KPIECE (OMPL's
// KPIECE1 with the knowledge rules only).

#include <ompl/control/planners/kpiece/KPIECE1.h>

#include "kautham/planners/PlannerEntry.h"
#include "kautham/planners/pkpiece/PKpiece.h"

namespace kautham::planners {

namespace {

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
        return ompl::base::PlannerPtr(std::make_shared<PKpiece>(context, resolved));
      });
}

PlannerRegistry::Entry oKpiece() {
  return omplPlannerEntry<ompl::control::KPIECE1>(
      "o-KPIECE",
      "the paper's baseline: KPIECE whose validity knows only whom the robot may touch "
      "(no after-effect checks, no uncertainty)",
      {goalBiasParameter(0.05), cellSizeParameter()}, [](physics::PlanningContext& context) {
        context.usePlanningRules(physics::ValidityRules::KnowledgeOnly);
      });
}

}  // namespace

void registerKpieceFamily(PlannerRegistry& registry) {
  registry.add(pKpiece());
  registry.add(oKpiece());
}

}  // namespace kautham::planners

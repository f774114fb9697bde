// p-KPIECE's registry entry: the paper's planner, ours, on OMPL's grid (its baseline o-KPIECE,
// OMPL's KPIECE1 with the knowledge rules only, is with the other OMPL planners).

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

}  // namespace

void registerPKpiece(PlannerRegistry& registry) { registry.add(pKpiece()); }

}  // namespace kautham::planners

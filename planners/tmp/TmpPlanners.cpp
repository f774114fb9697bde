// The task-and-motion-planning baseline's registry entries: TMP (the paper's TP column, after
// Srivastava et al. 2014) and TMP-U (TPU, with uncertainty, after Hadfield-Menell et al. 2015).

#include "kautham/planners/PlannerEntry.h"
#include "kautham/planners/tmp/TaskPlanner.h"

namespace kautham::planners {

namespace {

PlannerRegistry::Entry taskPlanner(const std::string& name, bool uncertainty,
                                   const std::string& summary) {
  return plannerEntry<tmp::TaskSettings>(
      name, summary, tmp::TaskSettings::parameters(uncertainty),
      [name](const tmp::TaskSettings& settings, physics::PlanningContext& context) {
        return ompl::base::PlannerPtr(std::make_shared<tmp::TaskPlanner>(context, name, settings));
      });
}

}  // namespace

void registerTaskPlanners(PlannerRegistry& registry) {
  registry.add(
      taskPlanner("TMP", false,
                  "task and motion planning baseline: moves obstructing objects away (grasp, "
                  "carry, place) with geometric plans until the pre-grasp is free"));
  registry.add(
      taskPlanner("TMP-U", true,
                  "TMP with uncertainty: movable objects inflated by k sigma of their pose "
                  "uncertainty"));
}

}  // namespace kautham::planners

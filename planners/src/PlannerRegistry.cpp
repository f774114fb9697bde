#include "kautham/planners/PlannerRegistry.h"

// The built-in planners, one line per file that registers some: a new built-in planner is a
// file defining `void registerSomething(PlannerRegistry&)` (see ompl/OmplControlPlanners.cpp) and a
// line here. Planners of other projects come from plugins instead (docs/plugins.md).
#define KAUTHAM_BUILTIN_PLANNERS(PLANNERS)                                            \
  PLANNERS(registerOmplControlPlanners)   /* KPIECE, RRT, SST, EST, PDST, o-KPIECE */ \
  PLANNERS(registerPKpiece)               /* p-KPIECE */                              \
  PLANNERS(registerGoalSteering)          /* goal-steering (p-KPIECE's, no search) */ \
  PLANNERS(registerOmplGeometricPlanners) /* RRTConnect, PRM, RRTstar, ... */         \
  PLANNERS(registerTaskPlanners)          /* TMP, TMP-U */

namespace kautham::planners {

#define KAUTHAM_DECLARE_BUILTIN(registerFunction) void registerFunction(PlannerRegistry& registry);
KAUTHAM_BUILTIN_PLANNERS(KAUTHAM_DECLARE_BUILTIN)
#undef KAUTHAM_DECLARE_BUILTIN

PlannerRegistry& plannerRegistry() {
  static PlannerRegistry registry = [] {
    PlannerRegistry builtins;
#define KAUTHAM_REGISTER_BUILTIN(registerFunction) registerFunction(builtins);
    KAUTHAM_BUILTIN_PLANNERS(KAUTHAM_REGISTER_BUILTIN)
#undef KAUTHAM_REGISTER_BUILTIN
    return builtins;
  }();
  return registry;
}

}  // namespace kautham::planners

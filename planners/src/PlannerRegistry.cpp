#include "kautham/planners/PlannerRegistry.h"

namespace kautham::planners {

PlannerRegistry& plannerRegistry() {
  static PlannerRegistry registry = [] {
    PlannerRegistry builtins;
    registerOmplControlPlanners(builtins);
    registerKpieceFamily(builtins);
    return builtins;
  }();
  return registry;
}

}  // namespace kautham::planners

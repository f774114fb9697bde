// Plugins that must fail to load, one library per case (tests/CMakeLists.txt builds this file
// with KAUTHAM_BAD_PLUGIN set to each): the host must report each, naming the file, exit 2.

#include <stdexcept>

#include <ompl/control/planners/rrt/RRT.h>

#include <kautham/planners/Plugin.h>

#if KAUTHAM_BAD_PLUGIN == 1
// Built for another ABI: it answers with its own version and registers nothing.
extern "C" __attribute__((visibility("default"))) unsigned kautham_register_planners(
    unsigned, kautham::planners::PlannerRegistry*) {
  return KAUTHAM_PLUGIN_ABI_VERSION + 41;
}

#elif KAUTHAM_BAD_PLUGIN == 2
// A shared library, but not a plugin: no registration function.
extern "C" __attribute__((visibility("default"))) int kautham_something_else() { return 2; }

#elif KAUTHAM_BAD_PLUGIN == 3
// Its registration throws.
KAUTHAM_PLANNER_PLUGIN(registry) {
  (void)registry;
  throw std::runtime_error("the plugin's calibration file is missing");
}

#elif KAUTHAM_BAD_PLUGIN == 4
// It registers a planner under a built-in planner's name.
KAUTHAM_PLANNER_PLUGIN(registry) {
  registry.add(kautham::planners::omplPlannerEntry<ompl::control::RRT>(
      "KPIECE", "an impostor", {kautham::planners::goalBiasParameter(0.05)}));
}

#elif KAUTHAM_BAD_PLUGIN == 5
// A parameter whose default is outside its range: the registry refuses the entry.
KAUTHAM_PLANNER_PLUGIN(registry) {
  registry.add(kautham::planners::omplPlannerEntry<ompl::control::RRT>(
      "BadRange", "a planner with a malformed parameter",
      {kautham::planners::goalBiasParameter(1.5)}));
}
#endif

#pragma once

// Writing a planner plugin: a shared library that exports one registration function with C
// linkage. Write it with KAUTHAM_PLANNER_PLUGIN:
//
//     #include <kautham/planners/Plugin.h>
//
//     KAUTHAM_PLANNER_PLUGIN(registry) {
//       registry.add(kautham::planners::plannerEntry<MySettings>("Mine", "what it is", ...));
//     }
//
// The host (`kautham --plugin FILE`, KAUTHAM_PLUGIN_PATH, the plugin folder next to the
// program; see PluginLoader.h and docs/plugins.md) calls the function with its plugin ABI
// version; the plugin registers its planners only if that is the version it was built for,
// and returns its own, so the host can say which side to rebuild.

#include "kautham/planners/PlannerEntry.h"
#include "kautham/planners/PlannerRegistry.h"

/// The plugin ABI version: raised whenever a change of the framework's public headers or
/// libraries would make a plugin built against the old ones misbehave.
#define KAUTHAM_PLUGIN_ABI_VERSION 1u

/// The name of the one function a plugin exports.
#define KAUTHAM_PLUGIN_SYMBOL "kautham_register_planners"

/// The type of that function: given the host's ABI version and registry, it registers the
/// plugin's planners (only when the versions are equal) and returns the plugin's ABI version.
/// A registration that fails throws; the host reports it and loads nothing of the plugin.
using KauthamRegisterPlanners = unsigned (*)(unsigned hostAbiVersion,
                                             kautham::planners::PlannerRegistry* registry);

/// Defines the plugin's registration function; the braces that follow are its body, with
/// `registry` (a kautham::planners::PlannerRegistry&) to add planners to.
#define KAUTHAM_PLANNER_PLUGIN(registry)                                                     \
  static void kauthamRegisterPluginPlanners(::kautham::planners::PlannerRegistry& registry); \
  extern "C" __attribute__((visibility("default"))) unsigned kautham_register_planners(      \
      unsigned hostAbiVersion, ::kautham::planners::PlannerRegistry* hostRegistry) {         \
    if (hostAbiVersion == KAUTHAM_PLUGIN_ABI_VERSION && hostRegistry != nullptr)             \
      kauthamRegisterPluginPlanners(*hostRegistry);                                          \
    return KAUTHAM_PLUGIN_ABI_VERSION;                                                       \
  }                                                                                          \
  static void kauthamRegisterPluginPlanners(::kautham::planners::PlannerRegistry& registry)

#pragma once

#include <ompl/base/Planner.h>

#include "kautham/core/FactoryRegistry.h"
#include "kautham/physics/PlanningContext.h"

namespace kautham::planners {

/// Planners by name: each entry declares its typed parameters and builds an OMPL planner
/// over a planning context (the physics of one query).
using PlannerRegistry = core::FactoryRegistry<ompl::base::PlannerPtr, physics::PlanningContext&>;

/// The registry with every built-in planner registered (the list is in PlannerRegistry.cpp),
/// and the planners of the plugins loaded so far (PluginLoader.h).
PlannerRegistry& plannerRegistry();

}  // namespace kautham::planners

#pragma once

#include <ompl/base/Planner.h>

#include "kautham/core/FactoryRegistry.h"
#include "kautham/physics/PlanningContext.h"

namespace kautham::planners {

/// Planners by name: each entry declares its typed parameters and builds an OMPL planner
/// over a planning context (the physics of one query).
using PlannerRegistry = core::FactoryRegistry<ompl::base::PlannerPtr, physics::PlanningContext&>;

/// The registry with every built-in planner registered.
PlannerRegistry& plannerRegistry();

/// Registers OMPL's control planners (KPIECE, RRT) over our physics.
void registerOmplControlPlanners(PlannerRegistry& registry);

/// Registers p-KPIECE and o-KPIECE (the paper's planner and its baseline).
void registerKpieceFamily(PlannerRegistry& registry);

}  // namespace kautham::planners

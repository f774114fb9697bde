#pragma once

#include <cstddef>
#include <memory>

#include "kautham/physics/PlanningContext.h"
#include "kautham/planners/PlanRequest.h"

namespace kautham::apps {

/// Builds the planning context of a query and checks its start: nothing interpenetrates and
/// the start state is valid. Throws core::InputError naming the file and line otherwise.
std::unique_ptr<physics::PlanningContext> makeCheckedContext(const core::Problem& problem,
                                                             std::size_t query,
                                                             const planners::PlanRequest& request);

}  // namespace kautham::apps

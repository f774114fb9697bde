#include "StartCheck.h"

#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace kautham::apps {

std::unique_ptr<physics::PlanningContext> makeCheckedContext(const core::Problem& problem,
                                                             std::size_t query,
                                                             const planners::PlanRequest& request) {
  std::unique_ptr<physics::PlanningContext> context;
  try {
    context = std::make_unique<physics::PlanningContext>(problem, query, request.propagation());
  } catch (const std::invalid_argument& e) {  // propagation settings that do not fit the physics
    throw core::InputError(problem.planner.where, e.what());
  }
  const core::SourceLocation& where = problem.queries[query].where;
  if (!context->startOverlaps().empty()) {
    std::string pairs;
    for (const physics::Overlap& o : context->startOverlaps())
      pairs += fmt::format("\n  {} and {} ({:.1f} mm)", o.first, o.second, 1000.0 * o.depth);
    throw core::InputError(where, "at the start, these interpenetrate; move them apart:" + pairs);
  }
  if (context->startViolation() != physics::Violation::None)
    throw core::InputError(where, std::string("the start state is invalid: ") +
                                      physics::toString(context->startViolation()));
  return context;
}

}  // namespace kautham::apps

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
  // Objects start asleep: one placed in the air would hang there until touched. A warning, as
  // a scene may mean it (an object set down by a hand the problem does not model).
  for (const physics::RestlessObject& r : context->restlessAtStart())
    fmt::print(stderr,
               "warning: {}: object '{}' does not rest where the start puts it: left alone it "
               "moves {:.1f} cm and tilts {:.2f} rad in a second (it floats, falls, slides or "
               "tips), yet it starts asleep and stays put until touched; set its <Home> so it "
               "stands on its support\n",
               where.str(), r.name, 100.0 * r.moved, r.tilted);
  return context;
}

}  // namespace kautham::apps

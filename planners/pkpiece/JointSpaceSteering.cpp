#include "kautham/planners/pkpiece/JointSpaceSteering.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace kautham::planners {

namespace {
// Where the motion aims, as close as the tree needs: the goal region is centimetres wide.
constexpr double kPositionTolerance = 0.003;  // m
constexpr double kAngleTolerance = 0.03;      // rad

int goalLinkOf(const physics::PlanningContext& context) {
  const std::optional<int> link = context.problem().robot.model.findLink(context.query().goal.link);
  if (!link)
    throw std::logic_error("JointSpaceSteering: no goal link " + context.query().goal.link);
  return *link;
}
}  // namespace

JointSpaceSteering::JointSpaceSteering(const physics::PlanningContext& context)
    : context_(context),
      joints_(context.problem(), context.query(), context.layout()),
      ik_(joints_, goalLinkOf(context)),
      mapping_(context.problem().robot.controls, context.layout().joints) {}

std::optional<NominalMotion> JointSpaceSteering::towards(const double* state,
                                                         const Eigen::Vector3d& position,
                                                         const Eigen::Matrix3d& orientation,
                                                         double maxSpeed) const {
  const physics::WorldLayout& layout = context_.layout();
  const double* q = state + layout.jointPositionIndex();
  const std::vector<double> now =
      joints_.coordinatesFor(std::vector<double>(q, q + layout.joints.size()));
  physics::PoseTarget target;
  target.position = position;
  const physics::GoalSpec& spec = context_.goal().spec();
  if (spec.approach) target.approach = orientation.col(2);
  target.levelAxis = spec.levelAxis;
  target.tolerance = kPositionTolerance;
  target.angleTolerance = kAngleTolerance;
  const std::optional<std::vector<double>> there = ik_.solve(target, now);
  if (!there) return std::nullopt;
  // Joint values of both ends through the same map, so joints no control moves cancel out.
  const std::vector<double> from = joints_.jointValues(now.data());
  const std::vector<double> to = joints_.jointValues(there->data());
  const auto& si = context_.spaceInformation();
  const double step = si->getPropagationStepSize();
  std::vector<double> perStep(from.size());
  for (std::size_t j = 0; j < from.size(); ++j) perStep[j] = (to[j] - from[j]) / step;
  // The control that covers the whole line in one step, and what each joint's speed limit
  // makes of it: the fewest steps that keep both within their limits.
  const std::vector<double> oneStep = mapping_.controlsFor(perStep);
  double largest = 0.0;
  for (double u : oneStep) largest = std::max(largest, std::abs(u));
  for (std::size_t j = 0; j < from.size(); ++j)
    if (layout.joints[j].maxVelocity > 0.0)
      largest = std::max(largest, std::abs(perStep[j]) / layout.joints[j].maxVelocity);
  const double distance = (position - layout.goalLinkPosition(state)).norm();
  return pacedMotion(*si, oneStep, largest, distance, maxSpeed);
}

}  // namespace kautham::planners

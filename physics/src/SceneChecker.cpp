#include "kautham/physics/SceneChecker.h"

#include <algorithm>

#include <ompl/base/spaces/RealVectorStateSpace.h>

namespace kautham::physics {

SceneChecker::SceneChecker(const ompl::base::SpaceInformationPtr& si, World& world,
                           const JointSpace& joints, int gripperLink, const double* scene,
                           const WorldValidityChecker* rules)
    : StateValidityChecker(si),
      world_(&world),
      rules_(rules),
      joints_(&joints),
      gripperLink_(gripperLink),
      scene_(scene, scene + world.layout().stateSize()) {}

void SceneChecker::setScene(const double* scene) {
  std::copy(scene, scene + scene_.size(), scene_.begin());
}

std::vector<double> SceneChecker::stateAt(const double* c) const {
  std::vector<double> state(scene_.size());
  const std::vector<double> q = joints_->jointValues(c);
  joints_->placeRobot(q, scene_.data(), state.data());
  if (held_)
    world_->layout().placeBody(state.data(), held_->body,
                               joints_->linkPose(q, gripperLink_) * held_->inGripper);
  return state;
}

void SceneChecker::setClearance(double metres, const double* start) {
  clearance_ = 0.0;
  shifts_.clear();
  if (!(metres > 0.0)) return;
  const std::vector<double> state = stateAt(start);
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {-1.0, 1.0}) {
      const Eigen::Vector3d shift = sign * metres * Eigen::Vector3d::Unit(axis);
      if (!touchesShifted(state, shift).any()) shifts_.push_back(shift);
    }
  clearance_ = metres;
}

RobotTouches SceneChecker::touchesShifted(std::vector<double> state,
                                          const Eigen::Vector3d& offset) const {
  const WorldLayout& layout = world_->layout();
  for (std::size_t b = 0; b < layout.bodies.size(); ++b) {
    const bool moving = layout.bodies[b].role == BodyRole::Robot || (held_ && held_->body == b);
    if (!moving) continue;
    double* p = state.data() + b * WorldLayout::kBodyStateSize + WorldLayout::kPosition;
    for (int k = 0; k < 3; ++k) p[k] += offset[k];
  }
  const std::lock_guard<std::mutex> lock(worldMutex_);
  world_->writeState(state.data());
  return obstaclesOnly(world_->robotTouches(heldBody()));
}

RobotTouches SceneChecker::obstaclesOnly(RobotTouches touches) const {
  if (obstacles_ != Obstacles::FixedOnly) return touches;
  // Movable objects are no obstacles here; the target still is.
  const WorldLayout& layout = world_->layout();
  touches.bodies.erase(std::remove_if(touches.bodies.begin(), touches.bodies.end(),
                                      [&layout, this](int b) {
                                        const auto body = static_cast<std::size_t>(b);
                                        return layout.bodies[body].role == BodyRole::Movable &&
                                               !solid_.count(body);
                                      }),
                       touches.bodies.end());
  return touches;
}

RobotTouches SceneChecker::touchesAt(const double* c) const { return touchesOf(stateAt(c)); }

RobotTouches SceneChecker::touchesOf(const std::vector<double>& state) const {
  ++checks_;
  // The shifted tests below move the robot by at most this much along an axis.
  const double reach = objectMargin_ > 0.0 ? objectMargin_ + clearance_ : clearance_;
  const std::lock_guard<std::mutex> lock(worldMutex_);
  world_->writeState(state.data());
  RobotTouches touches = obstaclesOnly(world_->robotTouchesNear(heldBody(), reach));
  for (const Eigen::Vector3d& shift : shifts_) {
    if (touches.any()) break;
    touches = obstaclesOnly(world_->robotTouchesShifted(shift));
  }
  if (objectMargin_ > 0.0 && !touches.any()) {
    const WorldLayout& layout = world_->layout();
    const double m = reach;
    for (const Eigen::Vector3d& shift : {Eigen::Vector3d(m, 0, 0), Eigen::Vector3d(-m, 0, 0),
                                         Eigen::Vector3d(0, m, 0), Eigen::Vector3d(0, -m, 0)}) {
      for (int body : obstaclesOnly(world_->robotTouchesShifted(shift)).bodies)
        if (layout.bodies[static_cast<std::size_t>(body)].role == BodyRole::Movable)
          touches.bodies.push_back(body);
      if (touches.any()) break;
    }
  }
  return touches;
}

bool SceneChecker::isValid(const ompl::base::State* state) const {
  const double* c = state->as<ompl::base::RealVectorStateSpace::StateType>()->values;
  const std::vector<double> placed = stateAt(c);
  if (workspace_ && !workspace_->contains(world_->layout().goalLinkPosition(placed.data())))
    return false;
  if (rules_ && rules_->check(placed.data()) != Violation::None) return false;
  return !touchesOf(placed).any();
}

}  // namespace kautham::physics

#include "kautham/core/Problem.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace kautham::core {

const char* toString(ObjectRole role) {
  switch (role) {
    case ObjectRole::Fixed:
      return "fixed";
    case ObjectRole::Movable:
      return "movable";
    case ObjectRole::Target:
      return "target";
  }
  return "?";
}

const ObjectInstance& Problem::target() const {
  for (const ObjectInstance& object : objects)
    if (object.role == ObjectRole::Target) return object;
  throw std::logic_error("problem has no target object");
}

std::optional<int> Problem::findObject(const std::string& objectName) const {
  for (std::size_t i = 0; i < objects.size(); ++i)
    if (objects[i].name == objectName) return static_cast<int>(i);
  return std::nullopt;
}

bool Problem::hasTarget() const {
  for (const ObjectInstance& object : objects)
    if (object.role == ObjectRole::Target) return true;
  return false;
}

Eigen::Vector3d Problem::goalPosition(const GoalRegion& goal) const {
  if (goal.isConfiguration()) {
    const std::vector<Eigen::Isometry3d> poses =
        robot.model.linkPoses(robot.home.isometry(), jointValuesFromControls(goal.controls));
    return poses.at(static_cast<std::size_t>(*robot.model.findLink(goal.link))).translation();
  }
  if (goal.relativeTo.empty()) return goal.offset;
  return objects.at(*findObject(goal.relativeTo)).home.isometry() * goal.offset;
}

std::optional<Eigen::Vector3d> Problem::goalApproach(const GoalRegion& goal) const {
  if (!goal.approach) return std::nullopt;
  if (goal.relativeTo.empty()) return *goal.approach;
  return objects.at(*findObject(goal.relativeTo)).home.isometry().linear() * *goal.approach;
}

std::vector<double> Problem::initialJointValues(const Query& query) const {
  if (!query.initJoints.empty()) return query.initJoints;
  if (query.init.empty()) return robot.initialJoints;
  return jointValuesFromControls(query.init);
}

std::vector<double> Problem::jointValuesFromControls(const std::vector<double>& controls) const {
  const std::vector<int> movable = robot.model.movableJoints();
  const Eigen::VectorXd normalized = robot.controls.normalizedConfiguration(controls);
  std::vector<double> values(movable.size());
  for (std::size_t i = 0; i < movable.size(); ++i) {
    const Joint& joint = robot.model.joints[movable[i]];
    values[i] =
        joint.lower + normalized[static_cast<Eigen::Index>(i)] * (joint.upper - joint.lower);
  }
  return values;
}

std::optional<int> Problem::supportObject() const {
  if (!interaction.supportObject.empty()) return findObject(interaction.supportObject);
  if (!hasTarget()) return std::nullopt;
  const Eigen::Vector3d below = target().home.position;
  std::optional<int> best;
  double bestTop = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < objects.size(); ++i) {
    if (objects[i].role != ObjectRole::Fixed) continue;
    const Eigen::AlignedBox3d box = boundsAtHome(objects[i]);
    const bool under = box.min().x() <= below.x() && below.x() <= box.max().x() &&
                       box.min().y() <= below.y() && below.y() <= box.max().y() &&
                       box.max().z() <= below.z();
    if (under && box.max().z() > bestTop) {
      bestTop = box.max().z();
      best = static_cast<int>(i);
    }
  }
  return best;
}

std::vector<CollisionShape> shapesAtHome(const ModelInstance& instance) {
  const KinematicModel& model = instance.model;
  const std::vector<Eigen::Isometry3d> poses = model.linkPoses(
      instance.home.isometry(), std::vector<double>(model.movableJoints().size(), 0.0));
  std::vector<CollisionShape> shapes;
  for (std::size_t i = 0; i < model.links.size(); ++i)
    for (const CollisionShape& c : model.links[i].collisions)
      shapes.push_back({c.shape, poses[i] * c.origin});
  return shapes;
}

Eigen::AlignedBox3d boundsAtHome(const ModelInstance& instance) {
  Eigen::AlignedBox3d box;  // empty
  for (const CollisionShape& c : shapesAtHome(instance)) box.extend(boundingBox(c.shape, c.origin));
  return box;
}

}  // namespace kautham::core

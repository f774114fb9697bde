#include "kautham/physics/WorldValidityChecker.h"

#include <cmath>
#include <stdexcept>
#include <variant>

#include "kautham/physics/WorldStateSpace.h"

namespace kautham::physics {

const char* toString(Violation violation) {
  switch (violation) {
    case Violation::None:
      return "none";
    case Violation::SimulationDiverged:
      return "simulation diverged";
    case Violation::RobotTouchedFixed:
      return "robot touched a fixed obstacle";
    case Violation::RobotTouchedTarget:
      return "robot touched the target";
    case Violation::TargetMoved:
      return "target moved";
    case Violation::OutsideWorkspace:
      return "end effector left the workspace";
    case Violation::JointLimit:
      return "joint beyond its limit";
    case Violation::JointTooFast:
      return "joint too fast";
    case Violation::LinkTooFast:
      return "robot link too fast";
    case Violation::ObjectTooFast:
      return "object too fast";
    case Violation::ObjectTilted:
      return "object tilted";
    case Violation::ObjectOffSupport:
      return "object left the table";
  }
  return "?";
}

bool isObjectRule(Violation violation) {
  switch (violation) {
    case Violation::RobotTouchedTarget:
    case Violation::TargetMoved:
    case Violation::ObjectTooFast:
    case Violation::ObjectTilted:
    case Violation::ObjectOffSupport:
      return true;
    case Violation::None:
    case Violation::SimulationDiverged:
    case Violation::RobotTouchedFixed:
    case Violation::OutsideWorkspace:
    case Violation::JointLimit:
    case Violation::JointTooFast:
    case Violation::LinkTooFast:
      return false;
  }
  return false;
}

namespace {
// An object whose centre drops this far below its start height has left the support surface
// (fallen off its edge, or through it).
constexpr double kDropTolerance = 0.02;
}  // namespace

WorldValidityChecker::WorldValidityChecker(const ompl::base::SpaceInformationPtr& si,
                                           std::shared_ptr<const WorldLayout> layout,
                                           const core::Problem& problem, const double* startState,
                                           ValidityRules rules)
    : StateValidityChecker(si),
      layout_(std::move(layout)),
      limits_(problem.interaction),
      robotLimits_(problem.kinodynamics),
      rules_(rules),
      workspace_(problem.workspace) {
  if (auto support = problem.supportObject())
    supportShapes_ = core::shapesAtHome(problem.objects[*support]);
  startHeights_.resize(layout_->bodies.size());
  restingSink_.assign(layout_->bodies.size(), 0.0);
  for (std::size_t b = 0; b < layout_->bodies.size(); ++b) {
    startHeights_[b] = WorldLayout::position(startState, b).z();
    if (layout_->bodies[b].role == BodyRole::Target) targetBody_ = b;
  }
  if (targetBody_) targetStart_ = WorldLayout::position(startState, *targetBody_);
}

bool WorldValidityChecker::isValid(const ompl::base::State* state) const {
  const Violation violation = check(WorldStateSpace::values(state));
  if (violation == Violation::None) return true;
  rejected_[static_cast<std::size_t>(violation)].fetch_add(1, std::memory_order_relaxed);
  return false;
}

std::array<std::uint64_t, kViolationKinds> WorldValidityChecker::rejectionCounts() const {
  std::array<std::uint64_t, kViolationKinds> counts{};
  for (std::size_t v = 0; v < kViolationKinds; ++v)
    counts[v] = rejected_[v].load(std::memory_order_relaxed);
  return counts;
}

Violation WorldValidityChecker::check(const double* state) const {
  return check(state, targetStart_);
}

Violation WorldValidityChecker::check(const double* state,
                                      const Eigen::Vector3d& targetReference) const {
  return check(state, targetReference, std::nullopt);
}

Violation WorldValidityChecker::check(const double* state, const Eigen::Vector3d& targetReference,
                                      std::optional<std::size_t> held) const {
  const unsigned flags = layout_->flags(state);
  if (flags & kSimulationDiverged) return Violation::SimulationDiverged;
  if (flags & kRobotTouchedFixed) return Violation::RobotTouchedFixed;
  if (flags & kRobotTouchedTarget) return Violation::RobotTouchedTarget;
  if (rules_ == ValidityRules::KnowledgeOnly) {
    if (!workspace_.contains(layout_->goalLinkPosition(state))) return Violation::OutsideWorkspace;
    return checkRobot(state);
  }
  if (targetBody_ && (WorldLayout::position(state, *targetBody_) - targetReference).norm() >
                         limits_.targetTolerance)
    return Violation::TargetMoved;
  if (!workspace_.contains(layout_->goalLinkPosition(state))) return Violation::OutsideWorkspace;
  if (Violation v = checkRobot(state); v != Violation::None) return v;
  for (std::size_t b = 0; b < layout_->bodies.size(); ++b)
    if (layout_->bodies[b].role == BodyRole::Movable && held != b)
      if (Violation v = checkObject(state, b); v != Violation::None) return v;
  return Violation::None;
}

std::optional<std::size_t> WorldValidityChecker::offendingObject(
    const double* state, const Eigen::Vector3d& targetReference,
    std::optional<std::size_t> held) const {
  const unsigned flags = layout_->flags(state);
  const bool targetMoved =
      targetBody_ && (WorldLayout::position(state, *targetBody_) - targetReference).norm() >
                         limits_.targetTolerance;
  if ((flags & kRobotTouchedTarget) || targetMoved) return targetBody_;
  for (std::size_t b = 0; b < layout_->bodies.size(); ++b)
    if (layout_->bodies[b].role == BodyRole::Movable && held != b &&
        checkObject(state, b) != Violation::None)
      return b;
  return std::nullopt;
}

bool WorldValidityChecker::onSupport(const Eigen::Vector3d& position) const {
  for (const core::CollisionShape& shape : supportShapes_) {
    const Eigen::Vector3d local = shape.origin.inverse() * position;
    if (const auto* box = std::get_if<core::Box>(&shape.shape)) {
      if (std::abs(local.x()) <= box->size.x() / 2 && std::abs(local.y()) <= box->size.y() / 2)
        return true;
    } else if (std::holds_alternative<core::Mesh>(shape.shape)) {
      // A mesh support: its own bounding box, seen from above.
      const Eigen::AlignedBox3d b = core::boundingBox(shape.shape, Eigen::Isometry3d::Identity());
      const Eigen::Array2d xy = local.head<2>().array();
      if ((xy >= b.min().head<2>().array()).all() && (xy <= b.max().head<2>().array()).all())
        return true;
    } else {
      const double radius = std::holds_alternative<core::Cylinder>(shape.shape)
                                ? std::get<core::Cylinder>(shape.shape).radius
                                : std::get<core::Sphere>(shape.shape).radius;
      if (local.head<2>().norm() <= radius) return true;
    }
  }
  return false;
}

Violation WorldValidityChecker::checkRobot(const double* state) const {
  const std::vector<JointInfo>& joints = layout_->joints;
  const double tolerance = robotLimits_.jointLimitTolerance;
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const double q = state[layout_->jointPositionIndex() + j];
    if (joints[j].limited &&
        !(q >= joints[j].lower - tolerance && q <= joints[j].upper + tolerance))
      return Violation::JointLimit;
    const double rate = state[layout_->jointVelocityIndex() + j];
    if (!joints[j].held &&
        !(std::abs(rate) <= joints[j].maxVelocity * robotLimits_.jointSpeedFactor))
      return Violation::JointTooFast;
  }
  for (std::size_t b = 0; b < layout_->bodies.size(); ++b)
    if (layout_->bodies[b].role == BodyRole::Robot &&
        WorldLayout::linearVelocity(state, b).norm() > robotLimits_.maxLinkSpeed)
      return Violation::LinkTooFast;
  return Violation::None;
}

void WorldValidityChecker::allowRestingSink(std::vector<double> sink) {
  if (sink.size() != layout_->bodies.size())
    throw std::invalid_argument("allowRestingSink: one depth per body expected");
  restingSink_ = std::move(sink);
}

Violation WorldValidityChecker::checkObject(const double* state, std::size_t body) const {
  if (WorldLayout::linearVelocity(state, body).norm() > limits_.maxObjectSpeed)
    return Violation::ObjectTooFast;
  if (core::tiltAngle(WorldLayout::orientation(state, body)) > limits_.maxTilt)
    return Violation::ObjectTilted;
  const Eigen::Vector3d p = WorldLayout::position(state, body);
  if (p.z() < startHeights_[body] - restingSink_[body] - kDropTolerance)
    return Violation::ObjectOffSupport;
  if (!supportShapes_.empty() && !onSupport(p)) return Violation::ObjectOffSupport;
  return Violation::None;
}

}  // namespace kautham::physics

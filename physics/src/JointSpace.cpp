#include "kautham/physics/JointSpace.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/QR>

namespace kautham::physics {

namespace {

/// The joint range a normalized unit spans; continuous joints (no limits) turn a full circle.
double span(const JointInfo& joint) { return joint.limited ? joint.upper - joint.lower : 2 * M_PI; }

}  // namespace

JointSpace::JointSpace(const core::Problem& problem, const core::Query& query,
                       const WorldLayout& layout)
    : problem_(&problem), layout_(&layout) {
  const Eigen::MatrixXd& K = problem.robot.controls.matrix;
  if (static_cast<std::size_t>(K.rows()) != layout.joints.size())
    throw std::logic_error("JointSpace: the control set does not match the robot's joints");
  const auto joints = static_cast<Eigen::Index>(layout.joints.size());
  matrix_.resize(joints, K.cols());
  lower_.resize(joints);
  upper_.resize(joints);
  for (Eigen::Index j = 0; j < joints; ++j) {
    const JointInfo& joint = layout.joints[static_cast<std::size_t>(j)];
    matrix_.row(j) = span(joint) * K.row(j);
    lower_[j] = joint.limited ? joint.lower : -std::numeric_limits<double>::infinity();
    upper_[j] = joint.limited ? joint.upper : std::numeric_limits<double>::infinity();
  }
  const std::vector<double> q = problem.initialJointValues(query);
  startJoints_ = Eigen::Map<const Eigen::VectorXd>(q.data(), joints);
  // q(c) is anchored at the start, so the start maps onto itself whatever c_start is; c_start
  // is Kautham's <Init> when given, else the coordinates that Kautham's mapping
  // n = K (c - 0.5) + o takes nearest to the start, so [0, 1] covers each joint's range.
  if (query.init.size() == dimension() && query.initJoints.empty()) {
    start_ = query.init;
  } else {
    Eigen::VectorXd normalized(joints);
    for (Eigen::Index j = 0; j < joints; ++j) {
      const JointInfo& joint = layout.joints[static_cast<std::size_t>(j)];
      normalized[j] = (startJoints_[j] - (joint.limited ? joint.lower : -M_PI)) / span(joint);
    }
    const Eigen::VectorXd c =
        (Eigen::VectorXd::Constant(K.cols(), 0.5) +
         K.completeOrthogonalDecomposition().solve(normalized - problem.robot.controls.offset))
            .cwiseMax(0.0)
            .cwiseMin(1.0);
    start_.assign(c.data(), c.data() + c.size());
  }

  double lever = 0.0;
  const Eigen::Vector3d base = problem.robot.home.position;
  for (int corner = 0; corner < 8; ++corner)
    lever = std::max(
        lever,
        (problem.workspace.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner)) - base)
            .norm());
  const std::vector<int> movable = problem.robot.model.movableJoints();
  double sum = 0.0;
  for (Eigen::Index i = 0; i < K.cols(); ++i)
    for (Eigen::Index j = 0; j < joints; ++j) {
      const bool prismatic =
          problem.robot.model.joints[static_cast<std::size_t>(movable[static_cast<std::size_t>(j)])]
              .type == core::JointType::Prismatic;
      const double reach = std::abs(matrix_(j, i)) * (prismatic ? 1.0 : lever);
      sum += reach * reach;
    }
  stretch_ = std::max(1e-6, std::sqrt(sum));

  const core::KinematicModel& model = problem.robot.model;
  for (const BodyInfo& body : layout.bodies) {
    int link = -1;
    if (body.role == BodyRole::Robot) {
      const std::string name = body.name.substr(body.name.find('/') + 1);
      link = model.findLink(name).value_or(-1);
      if (link < 0) throw std::logic_error("JointSpace: no robot link for body " + body.name);
    }
    bodyLink_.push_back(link);
  }
}

std::vector<double> JointSpace::jointValues(const double* c) const {
  const Eigen::Map<const Eigen::VectorXd> coordinates(c, matrix_.cols());
  const Eigen::Map<const Eigen::VectorXd> start(start_.data(), matrix_.cols());
  const Eigen::VectorXd q =
      (startJoints_ + matrix_ * (coordinates - start)).cwiseMax(lower_).cwiseMin(upper_);
  return {q.data(), q.data() + q.size()};
}

std::vector<double> JointSpace::coordinatesFor(const std::vector<double>& q) const {
  const Eigen::Map<const Eigen::VectorXd> joints(q.data(), matrix_.rows());
  const Eigen::Map<const Eigen::VectorXd> start(start_.data(), matrix_.cols());
  const Eigen::VectorXd c =
      (start + matrix_.completeOrthogonalDecomposition().solve(joints - startJoints_))
          .cwiseMax(0.0)
          .cwiseMin(1.0);
  return {c.data(), c.data() + c.size()};
}

Eigen::Isometry3d JointSpace::linkPose(const std::vector<double>& q, int link) const {
  const core::RobotInstance& robot = problem_->robot;
  return robot.model.linkPoses(robot.home.isometry(), q).at(static_cast<std::size_t>(link));
}

void JointSpace::placeRobot(const std::vector<double>& q, const double* scene,
                            double* state) const {
  const WorldLayout& layout = *layout_;
  std::copy(scene, scene + layout.stateSize(), state);
  const core::RobotInstance& robot = problem_->robot;
  const std::vector<Eigen::Isometry3d> poses = robot.model.linkPoses(robot.home.isometry(), q);
  for (std::size_t b = 0; b < layout.bodies.size(); ++b)
    if (bodyLink_[b] >= 0)
      layout.placeBody(state, b, poses[static_cast<std::size_t>(bodyLink_[b])]);
  std::copy(q.begin(), q.end(), state + layout.jointPositionIndex());
  std::fill(state + layout.jointVelocityIndex(), state + layout.flagsIndex(), 0.0);
  state[layout.flagsIndex()] = 0.0;
}

}  // namespace kautham::physics

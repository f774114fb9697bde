#pragma once

#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "kautham/core/Problem.h"
#include "kautham/physics/WorldLayout.h"

namespace kautham::physics {

/// The robot's configuration space as Kautham's geometric planners see it: one coordinate per
/// control of the control set, each in [0, 1]. Joint values are affine in them,
/// q = clamp(q_start + D K (c - c_start)), with K the control set's matrix and D the joint
/// ranges (core::ControlSet), so a degree of freedom that no control moves stays where the
/// query starts it, as the physics holds it. Without a .cntr file K = I and c is the joint's
/// position within its limits.
///
/// It also places the robot: a world state with the robot's bodies where forward kinematics
/// puts them and everything else copied from a scene state. No physics is stepped.
class JointSpace {
 public:
  JointSpace(const core::Problem& problem, const core::Query& query, const WorldLayout& layout);

  std::size_t dimension() const { return static_cast<std::size_t>(matrix_.cols()); }
  /// The coordinates of the query's start.
  const std::vector<double>& start() const { return start_; }
  /// Joint values (radians, metres), one per movable joint, at coordinates `c`.
  std::vector<double> jointValues(const double* c) const;
  /// The coordinates nearest (least squares, then clamped into [0, 1]) to joint values `q`.
  std::vector<double> coordinatesFor(const std::vector<double>& q) const;

  /// A bound on how far (m) any point of the robot moves per unit of coordinate distance
  /// (Euclidean): sqrt(sum over joints of (range * lever)^2), a revolute joint's lever being the
  /// distance from the robot's base to the far corner of the workspace. Sets the resolution of
  /// collision checks along a motion.
  double stretch() const { return stretch_; }

  /// Writes into `state` the scene state `scene` with the robot at joint values `q`, at rest.
  void placeRobot(const std::vector<double>& q, const double* scene, double* state) const;
  /// World pose of the robot link `link` (index into the model's links) at joint values `q`.
  Eigen::Isometry3d linkPose(const std::vector<double>& q, int link) const;
  const core::KinematicModel& model() const { return problem_->robot.model; }

 private:
  const core::Problem* problem_;
  const WorldLayout* layout_;
  Eigen::MatrixXd matrix_;  ///< D K: joint values per unit of each coordinate
  Eigen::VectorXd lower_, upper_;
  Eigen::VectorXd startJoints_;
  std::vector<double> start_;
  double stretch_ = 1.0;
  /// Per robot body of the layout: the model link at its top (-1 for objects).
  std::vector<int> bodyLink_;
};

}  // namespace kautham::physics

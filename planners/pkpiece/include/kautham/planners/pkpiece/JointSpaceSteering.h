#pragma once

#include <optional>

#include <Eigen/Geometry>

#include "kautham/physics/ControlMapping.h"
#include "kautham/physics/InverseKinematics.h"
#include "kautham/physics/JointSpace.h"
#include "kautham/physics/PlanningContext.h"
#include "kautham/planners/pkpiece/MotionEvaluator.h"

namespace kautham::planners {

/// A control that carries the goal link to a pose: inverse kinematics from the state's joint
/// values, then a straight line in joint space, as fast as the joints' speed limits allow.
///
/// Exact where a Jacobian is not: over a long motion an arm's Jacobian changes, and where the
/// arm moves its gripper little per joint turn (the YuMi) the linear estimate commands joint
/// turns of radians that carry the gripper far past its aim. The velocity motors reach the
/// commanded joint speed within the first step, so the line in joint space is what the
/// physics does, until something is touched.
class JointSpaceSteering {
 public:
  explicit JointSpaceSteering(const physics::PlanningContext& context);

  /// The motion that brings the goal link from `state` to `position`, its +z along
  /// `orientation`'s and (as the goal asks) its level axis level; with `maxSpeed` > 0 (m/s)
  /// the link's straight-line speed stays below it. None when inverse kinematics finds no
  /// such pose near the state's joint values.
  std::optional<NominalMotion> towards(const double* state, const Eigen::Vector3d& position,
                                       const Eigen::Matrix3d& orientation, double maxSpeed) const;

 private:
  const physics::PlanningContext& context_;
  physics::JointSpace joints_;
  physics::InverseKinematics ik_;
  physics::ControlMapping mapping_;
};

}  // namespace kautham::planners

#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "kautham/core/KinematicModel.h"
#include "kautham/core/Pose.h"
#include "kautham/core/Problem.h"

namespace kautham::core {

/// How a control set (.cntr) uses Kautham's base degrees of freedom: the translations X, Y, Z
/// and the rotation parameters X1, X2, X3 (Kautham's SE3 part).
struct BaseDofUse {
  bool named = false;  ///< the set names some of them (Kautham's "SE3 enabled")
  /// Kautham's own names are used (X rather than this project's base_X): only then do the
  /// rotation parameters X1, X2, X3 take Kautham's default of 0.5 when not given.
  bool kauthamNames = false;
  std::map<std::string, double> offset;  ///< offsets given, by name
  std::set<std::string> moved;           ///< names some <Control> moves
  SourceLocation where;                  ///< the .cntr file, for errors
};

/// Reads which of X, Y, Z, X1, X2, X3 a .cntr file names, ignoring the "robot/" prefix.
BaseDofUse scanBaseDofs(const std::filesystem::path& cntrFile);

/// Puts a model on Kautham's mobile base, as Kautham reads <Limits> and <Home>:
///  - <Limits> are in the world frame. Their corners are taken into the <Home> frame; an axis of
///    that frame where min equals max (or that no <Limits> constrains) is pinned at Home's
///    coordinate, every other one becomes a prismatic joint (base_X, base_Y, base_Z, along the
///    Home frame's axes) spanning the limits, so Home's translation does not add to them.
///  - X1, X2, X3 are Kautham's normalized rotation (a unit quaternion from three numbers in
///    [0, 1]; 0.5 when not given, if the set uses Kautham's names). With X1 = 0 it is a turn of 2
///    pi X3 about the Home frame's z: a control that moves X3 adds a revolute joint base_X3. A
///    rotation no control moves is a fixed turn of the robot on its base.
///  - Without a control set every <Limits> axis becomes a joint (one control each). With one that
///    names none of X, Y, Z, X1, X2, X3, the base stays at Home (the limits are unused).
/// Returns the base DOF names that have no joint (pinned or fixed), which a control set may name
/// and which are then ignored.
std::set<std::string> addMobileBase(KinematicModel& model, const std::vector<BaseAxisLimits>& axes,
                                    const Pose& home, const BaseDofUse* controls);

/// Kautham's quaternion of the rotation parameters X1, X2, X3 (each in [0, 1]).
Eigen::Quaterniond kauthamRotation(double x1, double x2, double x3);

}  // namespace kautham::core

#pragma once

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kautham/core/InputError.h"
#include "kautham/core/KinematicModel.h"

namespace kautham::core {

/// Kautham's control set (a `.cntr` file): the planner's controls are weighted combinations of
/// the robot's degrees of freedom, in normalized joint coordinates ([0, 1] spans each joint's
/// limits).
///
/// A configuration is q = clip(K (c - 0.5) + o, 0, 1) for normalized controls c in [0, 1]^m,
/// K the dof x m matrix whose columns are the controls (scaled by their eigValue) and o the
/// offset. A degree of freedom that no control moves (a zero row of K) stays at its offset:
/// that is how a gripper is held open while the arm pushes.
struct ControlSet {
  std::vector<std::string> names;  ///< one per control (a column of `matrix`)
  Eigen::MatrixXd matrix;          ///< K: one row per movable joint, in KinematicModel order
  Eigen::VectorXd offset;          ///< o: normalized value of every movable joint
  std::filesystem::path file;      ///< empty when the set was not read from a file
  SourceLocation where;            ///< the <Controls> element that asked for it

  /// Without a .cntr file: one control per movable joint, named after it (K = I, o = 0.5).
  static ControlSet onePerJoint(const KinematicModel& model);

  std::size_t size() const { return names.size(); }
  /// Whether some control moves the degree of freedom `dof` (else it is held at its offset).
  bool moves(std::size_t dof) const;
  /// Keeps the first `count` controls; every other control j stays at the normalized value
  /// `at[j]` for good (its share goes into the offset), so the configurations it reached there
  /// are unchanged.
  void keepFirst(std::size_t count, const std::vector<double>& at);
  /// Normalized configuration reached by normalized controls `controls` (one per control).
  Eigen::VectorXd normalizedConfiguration(const std::vector<double>& controls) const;
};

/// Reads a .cntr file for `model`. DOF names are the child link (or joint) name of a movable
/// joint, optionally prefixed by "robot/" as Kautham writes them; Kautham's base DOFs X, Y, Z
/// and X3 name the joints base_X, base_Y, base_Z and base_X3. Names in `ignored` (base DOFs
/// without a joint: a pinned axis, a fixed rotation) are accepted and have no effect. Errors
/// name the file and line.
ControlSet loadControlSet(const std::filesystem::path& file, const KinematicModel& model,
                          const SourceLocation& requestedAt,
                          const std::set<std::string>& ignored = {});

}  // namespace kautham::core

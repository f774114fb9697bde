#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "kautham/physics/WorldLayout.h"

namespace kautham::physics {

/// The space a side pre-grasp needs free: a box in the goal link's frame (between the open
/// fingers and along the final approach to the grasp) that no movable object may occupy.
/// The box is sampled on a grid of at most kSpacing between points, and each point is tested
/// against the collision shapes of the movable bodies at their poses in the state, so the
/// check needs no physics engine and gives the same answer in planning, replay and validate.
/// An object thinner than the spacing can slip between grid points; the shipped objects are
/// 6 cm or more across (docs/scenes.md).
class GoalFreeSpace {
 public:
  static constexpr double kSpacing = 0.01;  ///< m between grid points, at most

  /// Throws std::invalid_argument unless every side of `size` is positive.
  GoalFreeSpace(std::shared_ptr<const WorldLayout> layout, const Eigen::Vector3d& size,
                const Eigen::Vector3d& center);

  /// Names of the movable objects that occupy the box, with the goal link at `goalLink`.
  std::vector<std::string> occupants(const double* state, const Eigen::Isometry3d& goalLink) const;
  bool isFree(const double* state, const Eigen::Isometry3d& goalLink) const;
  /// How much of the box the objects fill, and which fills most.
  struct Occupancy {
    double fraction = 0.0;  ///< share of the grid points inside some movable object, in [0, 1]
    std::optional<std::size_t> largest;  ///< the body holding the most points (none if empty)
  };
  Occupancy occupancy(const double* state, const Eigen::Isometry3d& goalLink) const;

 private:
  /// The body's pose in the state, if any of its shapes can reach the box.
  std::optional<Eigen::Isometry3d> poseIfNear(std::size_t body, const double* state,
                                              const Eigen::Vector3d& boxCentre) const;
  bool occupies(std::size_t body, const double* state,
                const std::vector<Eigen::Vector3d>& worldPoints,
                const Eigen::Vector3d& boxCentre) const;

  std::shared_ptr<const WorldLayout> layout_;
  Eigen::Vector3d center_;
  double boundingRadius_;              ///< of the box, about its centre
  std::vector<Eigen::Vector3d> grid_;  ///< in the goal link's frame
  std::vector<std::size_t> movable_;   ///< bodies that may not be in the box
  std::vector<double> shapeRadius_;    ///< per layout shape: its bounding ball about its origin
};

}  // namespace kautham::physics

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
  /// A movable body's shapes (indices into the layout's), the radius of a ball about each
  /// shape's origin that holds it, and of one about the body's origin that holds them all:
  /// fixed by the layout, so worked out once.
  struct MovableBody {
    std::size_t body;
    std::vector<std::size_t> shapes;
    std::vector<double> shapeRadii;
    double reach;
  };
  /// A shape of a movable body near the box, with the map from world to its own frame, and
  /// its bounding ball in the goal link's frame (the grid's): a grid point outside the ball
  /// cannot be inside the shape and costs no transform.
  struct NearShape {
    const core::Shape* shape;
    std::size_t entry;  ///< in movable_
    Eigen::Isometry3d toShape;
    Eigen::Vector3d ballCentre;
    double ballRadiusSquared;
    bool mayHold(const Eigen::Vector3d& gridPoint) const {
      return (gridPoint - ballCentre).squaredNorm() <= ballRadiusSquared;
    }
  };
  /// The shapes of the bodies near the box with the goal link at `goalLink` whose bounding
  /// balls reach into it: most objects are nowhere near the gripper and are skipped whole.
  std::vector<NearShape> nearShapes(const double* state, const Eigen::Isometry3d& goalLink) const;
  /// Calls `visit(index)` for each grid point in the box around a near shape's ball (a
  /// row more on each side, so rounding loses none), until it returns false; returns
  /// whether it never did.
  template <typename Visit>
  bool forPointsAround(const NearShape& shape, Visit&& visit) const;
  /// Per entry of movable_: how many grid points lie inside that body; `anyInside` gets how
  /// many lie inside some body. One pass serves occupants() and occupancy().
  std::vector<std::size_t> pointsInside(const double* state, const Eigen::Isometry3d& goalLink,
                                        std::size_t& anyInside) const;

  std::shared_ptr<const WorldLayout> layout_;
  Eigen::Vector3d center_;
  Eigen::Vector3d halfSize_;
  double boundingRadius_;              ///< of the box, about its centre
  std::vector<Eigen::Vector3d> grid_;  ///< in the goal link's frame, x-major: (i, j, k)
  Eigen::Vector3i count_;              ///< grid points along each axis
  Eigen::Vector3d spacing_;            ///< between neighbouring grid points along each axis
  std::vector<MovableBody> movable_;   ///< bodies that may not be in the box
};

}  // namespace kautham::physics

#pragma once

#include <vector>

#include <ompl/util/RandomNumbers.h>
#include <Eigen/Geometry>

namespace kautham::planners::tmp {

/// An object's footprint on the table: a disc around its centre.
struct Footprint {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double radius = 0.0;  ///< m
};

/// Where the task planner may put an object it moves out of the way.
struct PlacementRules {
  Eigen::AlignedBox2d area;         ///< where the object's centre may go (the table, shrunk)
  std::vector<Footprint> occupied;  ///< the other objects, the target among them
  /// Polylines the gripper sweeps to the pre-grasp (a single point: a disc around it).
  std::vector<std::vector<Eigen::Vector2d>> corridors;
  double corridorHalfWidth = 0.08;  ///< m: half the gripper's width and a margin
  double gap = 0.02;                ///< m kept between footprints
};

/// Whether an object of `radius` at `centre` lies in the area, off every other footprint (by
/// the gap) and off every corridor.
bool isFreePlacement(const PlacementRules& rules, const Eigen::Vector2d& centre, double radius);

/// Placements drawn uniformly over the area (`tries` draws), in the order drawn, keeping those
/// that are free.
std::vector<Eigen::Vector2d> samplePlacements(const PlacementRules& rules, double radius, int tries,
                                              ompl::RNG& rng);

}  // namespace kautham::planners::tmp

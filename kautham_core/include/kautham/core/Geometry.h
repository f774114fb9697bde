#pragma once

#include <variant>
#include <vector>

#include <Eigen/Geometry>

namespace kautham::core {

/// Collision primitives, in the conventions of URDF (cylinders along their local z axis).
struct Box {
  Eigen::Vector3d size;  ///< full side lengths
};
struct Cylinder {
  double radius;
  double length;
};
struct Sphere {
  double radius;
};
using Shape = std::variant<Box, Cylinder, Sphere>;

/// A primitive placed in the frame of the link it belongs to.
struct CollisionShape {
  Shape shape;
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
};

/// Axis-aligned bounding box of a shape placed at `pose` in the world.
Eigen::AlignedBox3d boundingBox(const Shape& shape, const Eigen::Isometry3d& pose);

}  // namespace kautham::core

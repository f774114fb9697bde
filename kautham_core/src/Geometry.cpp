#include "kautham/core/Geometry.h"

namespace kautham::core {

namespace {

Eigen::Vector3d localHalfExtents(const Shape& shape) {
  struct HalfExtents {
    Eigen::Vector3d operator()(const Box& box) const { return box.size / 2.0; }
    Eigen::Vector3d operator()(const Cylinder& c) const {
      return {c.radius, c.radius, c.length / 2.0};
    }
    Eigen::Vector3d operator()(const Sphere& s) const {
      return Eigen::Vector3d::Constant(s.radius);
    }
  };
  return std::visit(HalfExtents{}, shape);
}

}  // namespace

Eigen::AlignedBox3d boundingBox(const Shape& shape, const Eigen::Isometry3d& pose) {
  // The box around a rotated box: each world half-extent is |R| times the local half-extents.
  const Eigen::Vector3d half = pose.linear().cwiseAbs() * localHalfExtents(shape);
  return {pose.translation() - half, pose.translation() + half};
}

}  // namespace kautham::core

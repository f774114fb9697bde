#include "kautham/core/Geometry.h"

namespace kautham::core {

namespace {

/// The world-aligned box around a shape placed at `pose`.
struct Bounds {
  const Eigen::Isometry3d& pose;

  /// The box around a rotated box: each world half-extent is |R| times the local half-extents.
  Eigen::AlignedBox3d centred(const Eigen::Vector3d& localHalf) const {
    const Eigen::Vector3d half = pose.linear().cwiseAbs() * localHalf;
    return {pose.translation() - half, pose.translation() + half};
  }
  Eigen::AlignedBox3d operator()(const Box& box) const { return centred(box.size / 2.0); }
  Eigen::AlignedBox3d operator()(const Cylinder& c) const {
    return centred({c.radius, c.radius, c.length / 2.0});
  }
  Eigen::AlignedBox3d operator()(const Sphere& s) const {
    return centred(Eigen::Vector3d::Constant(s.radius));
  }
  Eigen::AlignedBox3d operator()(const Mesh& mesh) const {
    // The hull's corners are the mesh's extreme points in every direction.
    Eigen::AlignedBox3d box;
    for (const Eigen::Vector3d& v : mesh.hull().vertices) box.extend(pose * v);
    return box;
  }
};

}  // namespace

Eigen::AlignedBox3d boundingBox(const Shape& shape, const Eigen::Isometry3d& pose) {
  return std::visit(Bounds{pose}, shape);
}

}  // namespace kautham::core

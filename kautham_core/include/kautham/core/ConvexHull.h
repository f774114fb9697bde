#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace kautham::core {

/// A convex polyhedron: its corner points, its faces as polygons, and the face planes.
struct ConvexHull {
  std::vector<Eigen::Vector3d> vertices;
  /// Indices into `vertices`, one convex polygon per face, counter-clockwise seen from outside.
  std::vector<std::vector<int>> faces;
  /// Per face, (n, d) with unit outward normal n: the face lies on n.x = d, the inside n.x < d.
  std::vector<Eigen::Vector4d> planes;

  /// Whether `point` is inside or on the hull, up to `tolerance` metres.
  bool contains(const Eigen::Vector3d& point, double tolerance = 1e-9) const;
};

/// The hull cannot be built: fewer than four points, or all of them (nearly) in one plane.
class DegenerateHullError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The convex hull of `points`, computed by Qhull (coplanar facets merged into polygons).
/// Throws DegenerateHullError when the points span no volume.
ConvexHull convexHull(const std::vector<Eigen::Vector3d>& points);

}  // namespace kautham::core

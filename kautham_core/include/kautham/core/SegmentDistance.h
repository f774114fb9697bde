#pragma once

#include <algorithm>

#include <Eigen/Core>

namespace kautham::core {

/// Distance from the point `p` to the segment from `a` to `b` (in the plane, or in space).
template <typename Vector>
double distanceToSegment(const Vector& p, const Vector& a, const Vector& b) {
  const Vector ab = b - a;
  const double length = ab.squaredNorm();
  const double t = length > 0.0 ? std::clamp((p - a).dot(ab) / length, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

}  // namespace kautham::core

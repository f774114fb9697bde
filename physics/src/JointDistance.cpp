#include "kautham/physics/JointDistance.h"

#include <algorithm>
#include <cmath>

namespace kautham::physics {

double jointDistance(const std::vector<JointInfo>& joints, const double* a, const double* b,
                     const std::vector<double>& ranges) {
  double sum = 0.0;
  for (std::size_t j = 0; j < ranges.size(); ++j) {
    double d = a[j] - b[j];
    if (!joints[j].limited) d = std::remainder(d, 2.0 * M_PI);
    d /= std::max(ranges[j], 1e-9);
    sum += d * d;
  }
  return std::sqrt(sum);
}

}  // namespace kautham::physics

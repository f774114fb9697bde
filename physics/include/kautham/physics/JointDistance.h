#pragma once

#include <vector>

#include "kautham/physics/WorldLayout.h"

namespace kautham::physics {

/// The distance between joint values `a` and `b` (one per joint of `joints`): each difference
/// over its `ranges` entry, a continuous joint's the short way round (its angle read back from
/// ODE jumps from pi to -pi), then the Euclidean norm. A configuration goal's measure.
double jointDistance(const std::vector<JointInfo>& joints, const double* a, const double* b,
                     const std::vector<double>& ranges);

}  // namespace kautham::physics

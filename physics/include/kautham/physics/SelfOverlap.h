#pragma once

#include <string>
#include <vector>

#include "kautham/core/Problem.h"

namespace kautham::physics {

/// Two links of one robot whose collision shapes interpenetrate.
struct LinkOverlap {
  std::string first;
  std::string second;
  double depth = 0.0;  ///< deepest penetration between their shapes, metres
};

/// Pairs of the robot's links whose shapes interpenetrate by more than `minDepth` when its
/// movable joints have `jointValues` (in movableJoints() order). Links that move as one (joined
/// by fixed joints) and links joined by a joint are not compared: they touch by design. The
/// physics never collides a robot with itself, so this is for warnings about a start that the
/// real robot could not take. Meshes are compared as their triangles, so a mesh wholly inside
/// another (no surfaces crossing) is not found. Uses ODE geometries of its own, no world.
std::vector<LinkOverlap> robotSelfOverlaps(const core::RobotInstance& robot,
                                           const std::vector<double>& jointValues, double minDepth);

}  // namespace kautham::physics

#pragma once

#include <memory>
#include <vector>

#include <ompl/control/PathControl.h>

#include "kautham/physics/PlanningContext.h"
#include "kautham/physics/Replay.h"

namespace kautham::physics {

/// A path of joint values (one vector per waypoint, radians or metres) turned into controls
/// that the physics executes: what a geometric planner's plan becomes, so that replay and
/// validation treat it as any other plan.
struct TrackedPath {
  std::vector<ControlStep> controls;
  std::vector<std::vector<double>> states;  ///< the world after each control (and at the start)
  Violation violation = Violation::None;    ///< the first the tracking met (it stops there)
  bool complete = false;                    ///< every waypoint reached, all states valid
};

struct TrackingSettings {
  double speed = 0.5;       ///< fraction of each joint's velocity limit
  double tolerance = 1e-3;  ///< rad or m: a waypoint counts as reached within this
  /// Controls a segment may take beyond its duration at the tracking speed, to settle.
  unsigned maxControlsPerWaypoint = 20;
};

/// Drives the robot along the straight joint-space segments between the waypoints through the
/// context's propagator, starting from `start` (a world state): a reference point moves along
/// the path at the tracking speed and waits at each waypoint (speeding up and slowing down at
/// what the weakest motor can give, where one cannot reach the speed within one control); each
/// control (the shortest
/// control duration) asks for the joint velocity that brings the joints from where they really
/// are to the reference. Stops at the first invalid state (full validity rules).
/// The tracked path as OMPL's control path over the context's world states (for the problem
/// definition, so OMPL's tools see the solution).
std::shared_ptr<ompl::control::PathControl> controlPath(
    const TrackedPath& tracked, const ompl::control::SpaceInformationPtr& si);

/// One control held for `steps` propagation steps from `start`, one propagation step at a time
/// as replays do, stopping at the first invalid state (full rules, the held object exempt).
TrackedPath holdControl(PlanningContext& context, const std::vector<double>& start,
                        const std::vector<double>& control, unsigned steps);

/// Appends `next` (tracked from where `path` ends) to `path`.
void append(TrackedPath& path, const TrackedPath& next);

TrackedPath trackJointPath(PlanningContext& context, const std::vector<double>& start,
                           const std::vector<std::vector<double>>& waypoints,
                           const TrackingSettings& settings = {});

}  // namespace kautham::physics

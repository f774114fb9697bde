#include "kautham/physics/PathTracking.h"

#include <algorithm>
#include <cmath>

#include <ompl/control/spaces/RealVectorControlSpace.h>

#include "kautham/physics/WorldStateSpace.h"

namespace kautham::physics {

TrackedPath holdControl(PlanningContext& context, const std::vector<double>& start,
                        const std::vector<double>& control, unsigned steps) {
  const ompl::control::SpaceInformation& si = *context.spaceInformation();
  ompl::base::State* from = si.allocState();
  ompl::base::State* to = si.allocState();
  ompl::control::Control* applied = si.allocControl();
  std::copy(start.begin(), start.end(), WorldStateSpace::values(from));
  std::copy(control.begin(), control.end(),
            applied->as<ompl::control::RealVectorControlSpace::ControlType>()->values);
  const WorldValidityChecker& checker = context.validityChecker();
  unsigned done = 0;
  Violation violation = Violation::None;
  while (done < steps && violation == Violation::None) {
    context.propagator().propagate(from, applied, si.getPropagationStepSize(), to);
    std::swap(from, to);
    ++done;
    violation =
        checker.check(WorldStateSpace::values(from), checker.targetStart(), context.world().held());
  }
  const double* end = WorldStateSpace::values(from);
  TrackedPath held;
  held.states = {start, std::vector<double>(end, end + context.layout().stateSize())};
  held.controls = {{control, done}};
  held.violation = violation;
  held.complete = violation == Violation::None;
  si.freeState(from);
  si.freeState(to);
  si.freeControl(applied);
  return held;
}

namespace {

/// Follows the path with a reference point that moves along it at the tracking speed: each
/// control lasts the shortest control duration and asks for the velocity that brings the joints
/// from where they really are to where the reference will be at its end. So motor lag is
/// corrected at every control rather than summed, and the robot slows into each waypoint (the
/// reference waits there), so it does not overshoot a corner of the path into an obstacle.
class Tracker {
 public:
  Tracker(PlanningContext& context, const std::vector<double>& start,
          const TrackingSettings& settings)
      : context_(context),
        layout_(context.layout()),
        si_(*context.spaceInformation()),
        settings_(settings),
        steps_(si_.getMinControlDuration()),
        duration_(steps_ * si_.getPropagationStepSize()),
        linkSpeedLimit_(context.problem().kinodynamics.maxLinkSpeed) {
    path_.states.push_back(start);
  }

  /// Follows the straight joint-space segment from `a` to `b`; false if the tracking must stop.
  bool follow(const std::vector<double>& a, const std::vector<double>& b) {
    const double length = segmentDuration(a, b);  // seconds at the tracking speed
    double elapsed = 0.0;
    for (unsigned n = 0; n < settings_.maxControlsPerWaypoint + length / duration_; ++n) {
      elapsed += duration_;
      const double share = length > 0.0 ? std::min(1.0, elapsed / length) : 1.0;
      std::vector<double> reference(a.size());
      for (std::size_t j = 0; j < a.size(); ++j) reference[j] = a[j] + share * (b[j] - a[j]);
      if (share >= 1.0 && largestError(b) <= settings_.tolerance) return true;
      if (!apply(reference)) return false;
    }
    return true;  // close enough: the next segment starts from where the joints are
  }

  TrackedPath result(bool complete) {
    path_.complete = complete && path_.violation == Violation::None;
    return std::move(path_);
  }

 private:
  /// Seconds the segment takes at the tracking speed: no joint faster than its share of its
  /// velocity limit, and no link faster than the same share of the link speed limit (a long arm
  /// on a mobile base would pass it at joint speeds that are fine for the joints).
  double segmentDuration(const std::vector<double>& a, const std::vector<double>& b) const {
    double duration = 0.0;
    for (std::size_t j = 0; j < a.size(); ++j)
      duration = std::max(
          duration, std::abs(b[j] - a[j]) / (settings_.speed * layout_.joints[j].maxVelocity));
    return std::max(duration, linkTravel(a, b) / (settings_.speed * linkSpeedLimit_));
  }

  /// The longest distance (m) a robot link's origin travels along the segment.
  double linkTravel(const std::vector<double>& a, const std::vector<double>& b) const {
    constexpr int kSamples = 8;
    const core::RobotInstance& robot = context_.problem().robot;
    std::vector<Eigen::Isometry3d> previous = robot.model.linkPoses(robot.home.isometry(), a);
    std::vector<double> travel(previous.size(), 0.0);
    for (int i = 1; i <= kSamples; ++i) {
      std::vector<double> q(a.size());
      for (std::size_t j = 0; j < a.size(); ++j) q[j] = a[j] + (b[j] - a[j]) * i / kSamples;
      const std::vector<Eigen::Isometry3d> poses = robot.model.linkPoses(robot.home.isometry(), q);
      for (std::size_t l = 0; l < poses.size(); ++l)
        travel[l] += (poses[l].translation() - previous[l].translation()).norm();
      previous = poses;
    }
    return *std::max_element(travel.begin(), travel.end());
  }

  const double* joints() const { return path_.states.back().data() + layout_.jointPositionIndex(); }

  double largestError(const std::vector<double>& target) const {
    double largest = 0.0;
    for (std::size_t j = 0; j < target.size(); ++j)
      largest = std::max(largest, std::abs(target[j] - joints()[j]));
    return largest;
  }

  /// One control towards `reference` (holdControl: the plan replays bit for bit).
  bool apply(const std::vector<double>& reference) {
    std::vector<double> velocities(reference.size());
    for (std::size_t j = 0; j < reference.size(); ++j)
      velocities[j] = (reference[j] - joints()[j]) / duration_;
    std::vector<double> u = context_.propagator().mapping().controlsFor(velocities);
    for (double& value : u) value = std::clamp(value, -1.0, 1.0);
    const TrackedPath step = holdControl(context_, path_.states.back(), u, steps_);
    append(path_, step);
    return step.complete;
  }

  PlanningContext& context_;
  const WorldLayout& layout_;
  const ompl::control::SpaceInformation& si_;
  TrackingSettings settings_;
  unsigned steps_;         ///< propagation steps per control: the shortest a control may last
  double duration_;        ///< seconds per control
  double linkSpeedLimit_;  ///< m/s
  TrackedPath path_;
};

}  // namespace

TrackedPath trackJointPath(PlanningContext& context, const std::vector<double>& start,
                           const std::vector<std::vector<double>>& waypoints,
                           const TrackingSettings& settings) {
  Tracker tracker(context, start, settings);
  const WorldLayout& layout = context.layout();
  std::vector<double> from(start.begin() + static_cast<long>(layout.jointPositionIndex()),
                           start.begin() + static_cast<long>(layout.jointVelocityIndex()));
  for (const std::vector<double>& waypoint : waypoints) {
    if (!tracker.follow(from, waypoint)) return tracker.result(false);
    from = waypoint;
  }
  return tracker.result(true);
}

std::shared_ptr<ompl::control::PathControl> controlPath(
    const TrackedPath& tracked, const ompl::control::SpaceInformationPtr& si) {
  auto path = std::make_shared<ompl::control::PathControl>(si);
  ompl::base::State* state = si->allocState();
  const auto copy = [&](const std::vector<double>& values) {
    std::copy(values.begin(), values.end(), WorldStateSpace::values(state));
  };
  copy(tracked.states.front());
  path->append(state);
  ompl::control::Control* control = si->allocControl();
  for (std::size_t i = 0; i < tracked.controls.size(); ++i) {
    const ControlStep& step = tracked.controls[i];
    std::copy(step.values.begin(), step.values.end(),
              control->as<ompl::control::RealVectorControlSpace::ControlType>()->values);
    copy(tracked.states[i + 1]);
    path->append(state, control, step.steps * si->getPropagationStepSize());
  }
  si->freeControl(control);
  si->freeState(state);
  return path;
}

void append(TrackedPath& path, const TrackedPath& next) {
  path.controls.insert(path.controls.end(), next.controls.begin(), next.controls.end());
  path.states.insert(path.states.end(), next.states.begin() + 1, next.states.end());
  path.violation = next.violation;
  path.complete = next.complete;
}

}  // namespace kautham::physics

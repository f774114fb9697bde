#include "kautham/physics/PathTracking.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <ompl/control/spaces/RealVectorControlSpace.h>

#include "kautham/core/JointInertia.h"
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
    const Profile profile = profileOf(a, b);
    double elapsed = 0.0;
    for (unsigned n = 0; n < settings_.maxControlsPerWaypoint + profile.duration / duration_; ++n) {
      elapsed += duration_;
      const double share = profile.share(elapsed);
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
  /// How far along a segment (0 to 1) the reference is after t seconds: it speeds up at a
  /// constant rate, cruises, and slows down at the same rate into the segment's end.
  struct Profile {
    double rate = 0.0;          ///< share per second while cruising
    double acceleration = 0.0;  ///< share per second^2; infinite: no ramps
    double ramp = 0.0;          ///< seconds of each ramp
    double duration = 0.0;      ///< seconds from end to end

    double share(double t) const {
      if (duration <= 0.0 || t >= duration) return 1.0;
      if (ramp <= 0.0) return std::min(1.0, t * rate);
      if (t < ramp) return 0.5 * acceleration * t * t;
      const double left = duration - t;
      if (left < ramp) return 1.0 - 0.5 * acceleration * left * left;
      return 0.5 * acceleration * ramp * ramp + rate * (t - ramp);
    }
  };

  /// The segment's profile. Without ramps the reference starts at the tracking speed, so every
  /// joint is asked for its full speed within one control; that is kept where every motor can
  /// give it (so plans of robots with strong motors are what they were). Where one cannot (a heavy
  /// mobile base on a weak motor), the whole reference ramps at what the weakest joint manages
  /// with half its effort (the other half holds it against the rest of the robot's reactions):
  /// a joint that lags while the others run ahead leaves the straight segment, which is all the
  /// geometric planner checked: Kautham's TX90 on its mobile base (53 kg on carriages of its
  /// mass, 100 N motors) strayed 5 cm from its path into a column.
  Profile profileOf(const std::vector<double>& a, const std::vector<double>& b) const {
    Profile profile;
    profile.duration = segmentDuration(a, b);
    if (profile.duration <= 0.0) return profile;
    profile.rate = 1.0 / profile.duration;
    constexpr double kEffortShare = 0.5;
    const core::RobotInstance& robot = context_.problem().robot;
    const std::vector<double> atA = core::jointInertias(robot.model, robot.home.isometry(), a);
    const std::vector<double> atB = core::jointInertias(robot.model, robot.home.isometry(), b);
    const std::vector<int> movable = robot.model.movableJoints();
    double acceleration = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < a.size(); ++j) {
      const double delta = std::abs(b[j] - a[j]);
      const double inertia = std::max(atA[j], atB[j]);
      if (delta <= 0.0 || inertia <= 0.0) continue;
      const double effort = robot.model.joints[static_cast<std::size_t>(movable[j])].maxEffort;
      acceleration = std::min(acceleration, kEffortShare * effort / inertia / delta);
    }
    if (profile.rate / acceleration <= duration_) return profile;
    profile.acceleration = acceleration;
    profile.ramp = std::min(profile.rate / acceleration, std::sqrt(1.0 / acceleration));
    profile.rate = acceleration * profile.ramp;
    profile.duration = profile.ramp + 1.0 / profile.rate;
    return profile;
  }

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

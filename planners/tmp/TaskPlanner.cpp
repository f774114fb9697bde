#include "kautham/planners/tmp/TaskPlanner.h"

#include <algorithm>
#include <cmath>

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>

#include "kautham/physics/WorldStateSpace.h"
#include "kautham/planners/geometric/JointSpaceGoals.h"

namespace kautham::planners::tmp {

namespace {

using core::Parameter;

/// Collision checks an IK solve is worth (Levenberg-Marquardt with numerical derivatives).
constexpr double kIkSolveWork = 10.0;
/// m: a grasp holds when the gripper's origin is this close to the object's bounding box.
constexpr double kGraspReach = 0.02;
/// m: a placed object is released this high above where it stood, and drops onto the table.
constexpr double kDropHeight = 0.005;
/// m the gripper lifts a grasped object straight up before carrying it.
constexpr double kLiftHeight = 0.03;
/// Propagation steps the arm holds still after a release while the object settles.
constexpr unsigned kSettleSteps = 10;
/// Before a release the arm holds still until the object moves slower than this (m/s), for
/// at most kMaxStopSteps propagation steps.
constexpr double kRestSpeed = 0.005;
constexpr unsigned kMaxStopSteps = 20;
/// Placements drawn for each object moved; of those, how many within the arm's reach the
/// planner tries to carry it to, and how many it checks for reach at most (IK is not free).
constexpr int kPlacementDraws = 600;
constexpr std::size_t kPlacementsTried = 25;
constexpr std::size_t kReachChecks = 120;
/// When no place off every corridor is reachable, places need keep off only the latest one
/// (and the pre-grasp).
constexpr std::size_t kRecentCorridors = 1;

physics::PoseTarget pose(const Eigen::Isometry3d& gripper, double tolerance) {
  physics::PoseTarget target;
  target.position = gripper.translation();
  target.approach = gripper.linear().col(2);
  target.tolerance = tolerance;
  target.angleTolerance = 0.05;
  return target;
}

}  // namespace

core::SettingsParameters<TaskSettings> TaskSettings::parameters(bool withUncertainty) {
  core::SettingsParameters<TaskSettings> table;
  table
      .add(&TaskSettings::subQueryWork,
           Parameter::integer("sub_query_work")
               .byDefault(kDefaultSubQueryWork)
               .range(100, 1000000000)
               .describe("work each geometric sub-query (a reach, a carry) may take at most, in "
                         "collision checks (an IK solve counts as 10): counted, not timed, so "
                         "a fixed seed gives the same plan on a busy machine"))
      .add(&TaskSettings::maxMoves, Parameter::integer("max_moves")
                                        .byDefault(20)
                                        .range(0, 1000)
                                        .describe("objects moved out of the way at most"))
      .add(&TaskSettings::speed,
           Parameter::real("speed").byDefault(0.5).range(0.01, 1.0).describe(
               "joint speed along every path, as a fraction of each joint's velocity limit"))
      .add(&TaskSettings::clearance,
           Parameter::real("clearance")
               .byDefault(0.002)
               .range(0.0, 0.1)
               .describe("m the robot (and what it carries) keeps from every obstacle"))
      .add(&TaskSettings::graspGap,
           Parameter::real("grasp_gap")
               .byDefault(0.01)
               .range(0.0, 0.02)
               .describe("m between an object's top and the gripper's origin when grasping it"))
      .add(&TaskSettings::uncertainty,
           Parameter::flag("uncertainty")
               .byDefault(withUncertainty ? 1 : 0)
               .describe("inflate movable objects by their pose uncertainty (TMP-U)"))
      .add(&TaskSettings::sigmas,
           Parameter::real("sigmas").byDefault(3.0).range(0.0, 10.0).describe(
               "k: the inflation is k standard deviations of each object's x and y"));
  return table;
}

TaskPlanner::TaskPlanner(physics::PlanningContext& context, const std::string& name,
                         TaskSettings settings)
    : Planner(context.spaceInformation(), name),
      context_(context),
      settings_(settings),
      query_(context),
      motionPlanner_(std::make_shared<ompl::geometric::RRTConnect>(query_.spaceInformation())) {
  specs_.approximateSolutions = true;
  addPlannerProgressProperty("objects_moved INTEGER", [this] { return std::to_string(moves_); });
  addPlannerProgressProperty("sub_queries INTEGER", [this] { return std::to_string(subQueries_); });
  addPlannerProgressProperty("collision_checks INTEGER",
                             [this] { return std::to_string(query_.checker().checks()); });
}

void TaskPlanner::clear() {
  Planner::clear();
  motionPlanner_->clear();
  plan_ = {};
  corridors_.clear();
  unmovable_.clear();
  placed_.clear();
  outOfReach_.clear();
  moves_ = 0;
  subQueries_ = 0;
}

std::vector<double> TaskPlanner::coordinatesNow() const {
  const physics::WorldLayout& layout = context_.layout();
  const auto first = now().begin() + static_cast<long>(layout.jointPositionIndex());
  return query_.joints().coordinatesFor(
      std::vector<double>(first, first + static_cast<long>(layout.joints.size())));
}

ompl::base::GoalPtr TaskPlanner::poseGoal(const physics::PoseTarget& target) const {
  auto goal = std::make_shared<geometric::PoseGoal>(query_.spaceInformation(), query_.ik(), target);
  goal->seedNear(coordinatesNow());
  return goal;
}

bool TaskPlanner::withinReach(const physics::PoseTarget& target) {
  // Kinematics only: from where the arm is, then from spread-out seeds.
  constexpr int kSeeds = 30;
  std::vector<double> seed = coordinatesNow();
  for (int i = 0; i < kSeeds; ++i) {
    if (query_.ik().solve(target, seed)) return true;
    for (double& c : seed) c = rng_.uniform01();
  }
  return false;
}

bool TaskPlanner::reachable(const ompl::base::Goal& goal) {
  // PoseGoal samples by IK (valid and collision-free, or a state out of the bounds).
  const auto& si = query_.spaceInformation();
  query_.checker().setScene(now().data());
  ompl::base::ScopedState<> sample(si->getStateSpace());
  static_cast<const geometric::PoseGoal&>(goal).sampleGoal(sample.get());
  return si->satisfiesBounds(sample.get());
}

std::optional<geometric::CoordinatePath> TaskPlanner::planTo(const ompl::base::GoalPtr& goal,
                                                             const Ptc& ptc, double share) {
  ++subQueries_;
  query_.checker().setScene(now().data());
  // Counted, not timed: a budget in seconds made outcomes depend on the machine's load. Time
  // goes to collision checks (13,000 to 18,000 a second here) and, while goals are sampled, to IK.
  const double budget = share * static_cast<double>(settings_.subQueryWork);
  const std::uint64_t checks = query_.checker().checks();
  const std::uint64_t solves = query_.ik().solves();
  const ompl::base::PlannerTerminationCondition spent([&] {
    return static_cast<double>(query_.checker().checks() - checks) +
               kIkSolveWork * static_cast<double>(query_.ik().solves() - solves) >
           budget;
  });
  return query_.plan(coordinatesNow(), goal, *motionPlanner_,
                     ompl::base::plannerOrTerminationCondition(ptc, spent), true);
}

bool TaskPlanner::execute(const geometric::CoordinatePath& path, physics::GripperAction action,
                          int object) {
  std::vector<std::vector<double>> joints = query_.jointValues(path);
  joints.erase(joints.begin());  // where the arm already is
  physics::TrackingSettings tracking;
  tracking.speed = settings_.speed;
  physics::TrackedPath tracked = physics::trackJointPath(context_, now(), joints, tracking);
  // A path the physics cannot follow within the rules (the tracked arm strays more than the
  // clearance and touches something, say) is dropped, like a sub-query that found nothing:
  // the plan so far stays valid, and the caller may plan again.
  if (!tracked.complete) {
    OMPL_DEBUG("%s: dropped a path the arm could not follow (%s)", getName().c_str(),
               physics::toString(tracked.violation));
    return false;
  }
  if (!tracked.controls.empty()) {
    tracked.controls.front().action = action;
    tracked.controls.front().object = object;
  }
  physics::append(plan_, tracked);
  return true;
}

bool TaskPlanner::holdStill(physics::GripperAction action, unsigned steps) {
  const std::vector<double> still(context_.propagator().mapping().size(), 0.0);
  physics::TrackedPath held = physics::holdControl(context_, now(), still, steps);
  held.controls.front().action = action;
  physics::append(plan_, held);
  return held.complete;
}

std::optional<std::size_t> TaskPlanner::obstruction(const Ptc& ptc) {
  // Where would the arm go if no movable object were in the way? Objects this planner put
  // down stay solid if a way around them exists: they were placed off the corridors found so
  // far, and taking one again only moves the clutter in circles.
  // Objects it cannot move are obstacles like the fixed ones.
  physics::SceneChecker& checker = query_.checker();
  std::set<std::size_t> stuck = unmovable_;
  stuck.insert(outOfReach_.begin(), outOfReach_.end());
  std::set<std::size_t> solid = stuck;
  solid.insert(placed_.begin(), placed_.end());
  checker.setObstacles(physics::Obstacles::FixedOnly, solid);
  std::optional<geometric::CoordinatePath> free =
      planTo(query_.problemGoal(false, coordinatesNow()), ptc);
  if (!free && solid.size() > stuck.size()) {
    checker.setObstacles(physics::Obstacles::FixedOnly, stuck);
    free = planTo(query_.problemGoal(false, coordinatesNow()), ptc);
  }
  checker.setObstacles(physics::Obstacles::Everything);
  if (!free) return std::nullopt;

  const physics::WorldLayout& layout = context_.layout();
  corridors_.emplace_back();
  std::vector<Eigen::Vector2d>& corridor = corridors_.back();
  const ompl::base::StateSpacePtr& space = query_.spaceInformation()->getStateSpace();
  ompl::base::ScopedState<> a(space), b(space), between(space);
  auto* values = between->as<ompl::base::RealVectorStateSpace::StateType>()->values;
  std::optional<std::size_t> first;
  for (std::size_t i = 0; i + 1 < free->size(); ++i) {
    std::copy((*free)[i].begin(), (*free)[i].end(),
              a->as<ompl::base::RealVectorStateSpace::StateType>()->values);
    std::copy((*free)[i + 1].begin(), (*free)[i + 1].end(),
              b->as<ompl::base::RealVectorStateSpace::StateType>()->values);
    const unsigned pieces = std::max(1u, space->validSegmentCount(a.get(), b.get()));
    for (unsigned k = 0; k <= pieces; ++k) {
      space->interpolate(a.get(), b.get(), static_cast<double>(k) / pieces, between.get());
      const std::vector<double> state = checker.stateAt(values);
      const Eigen::Vector3d tcp = layout.goalLinkPosition(state.data());
      corridor.emplace_back(tcp.x(), tcp.y());
      if (first) continue;
      for (int body : checker.touchesAt(values).bodies)
        if (layout.bodies[static_cast<std::size_t>(body)].role == physics::BodyRole::Movable &&
            !stuck.count(static_cast<std::size_t>(body))) {
          first = static_cast<std::size_t>(body);
          break;
        }
    }
  }
  if (first) return first;
  // Nothing on the way: what fills the space between the fingers at the pre-grasp?
  const auto blocker =
      context_.goal().freeSpaceBlocker(checker.stateAt(free->back().data()).data());
  if (!blocker) clearPath_ = free;  // the way is clear after all (the direct try was short)
  if (blocker && outOfReach_.count(*blocker)) {
    OMPL_DEBUG("%s: %s fills the pre-grasp's free space and is out of reach", getName().c_str(),
               layout.bodies[*blocker].name.c_str());
    return std::nullopt;
  }
  return blocker;
}

std::optional<physics::PoseTarget> TaskPlanner::graspFromAbove(std::size_t object) {
  // The gripper's origin over the top's centre, its approach axis down; for an object beyond
  // the reach of a vertical approach, tilted outwards (away from the arm's base) by up to 40
  // degrees, the origin backed off along the approach.
  const Eigen::AlignedBox3d box = context_.layout().bounds(object, now().data());
  const Eigen::Vector3d top(box.center().x(), box.center().y(), box.max().z());
  Eigen::Vector3d outwards = top - context_.problem().robot.home.position;
  outwards.z() = 0.0;
  outwards = outwards.norm() > 1e-9 ? outwards.normalized() : Eigen::Vector3d::UnitX();
  for (const double tilt : {0.0, 0.35, 0.7}) {
    physics::PoseTarget target;
    target.approach = -std::cos(tilt) * Eigen::Vector3d::UnitZ() + std::sin(tilt) * outwards;
    target.position = top - *target.approach * settings_.graspGap;
    target.tolerance = 0.005;
    target.angleTolerance = 0.1;
    if (withinReach(target)) return target;
  }
  return std::nullopt;
}

bool TaskPlanner::grasp(std::size_t object, const Ptc& ptc) {
  const physics::WorldLayout& layout = context_.layout();
  // Out of the arm's reach from above, it never will be: an obstacle from now on. In reach
  // but with no collision-free grasp (its neighbours in the fingers' way), it may be later.
  const std::optional<physics::PoseTarget> target = graspFromAbove(object);
  if (!target) {
    OMPL_DEBUG("%s: %s out of reach from above", getName().c_str(),
               layout.bodies[object].name.c_str());
    outOfReach_.insert(object);
    return false;
  }
  const ompl::base::GoalPtr goal = poseGoal(*target);
  if (!reachable(*goal)) {
    OMPL_DEBUG("%s: no collision-free grasp of %s", getName().c_str(),
               layout.bodies[object].name.c_str());
    return false;
  }
  // Another path, if the physics could not follow the first (RRTConnect's paths differ).
  constexpr int kPathTries = 3;
  bool reached = false;
  for (int attempt = 0; attempt < kPathTries && !reached && !ptc(); ++attempt) {
    const auto path = planTo(goal, ptc);
    if (!path) {
      OMPL_DEBUG("%s: no path to grasp %s", getName().c_str(), layout.bodies[object].name.c_str());
      return false;
    }
    reached = execute(*path, physics::GripperAction::None, -1);
  }
  if (!reached) return false;

  physics::World& world = context_.world();
  world.writeState(now().data());
  if (!world.attach(object, kGraspReach)) {
    OMPL_DEBUG("%s: %s out of the gripper's reach", getName().c_str(),
               layout.bodies[object].name.c_str());
    return false;
  }
  const std::vector<double> q = query_.joints().jointValues(coordinatesNow().data());
  const Eigen::Isometry3d gripperNow = query_.joints().linkPose(q, query_.gripperLink());
  query_.checker().hold(
      physics::HeldObject{object, gripperNow.inverse() * layout.linkPose(now().data(), object)});
  return true;
}

bool TaskPlanner::lift(std::size_t object) {
  // Straight up off the table: standing on it, the held object touches it, and no motion
  // planner starts from a state in contact.
  const std::vector<double> from = coordinatesNow();
  const std::vector<double> q = query_.joints().jointValues(from.data());
  Eigen::Isometry3d up = query_.joints().linkPose(q, query_.gripperLink());
  up.translation().z() += kLiftHeight;
  const auto to = query_.ik().solve(pose(up, 0.003), from);
  if (!to) return false;
  ompl::base::ScopedState<> lifted(query_.spaceInformation()->getStateSpace());
  std::copy(to->begin(), to->end(),
            lifted->as<ompl::base::RealVectorStateSpace::StateType>()->values);
  if (!query_.spaceInformation()->isValid(lifted.get())) return false;
  return execute({from, *to}, physics::GripperAction::Grasp, static_cast<int>(object));
}

bool TaskPlanner::carryAway(std::size_t object, const Ptc& ptc) {
  if (!lift(object)) {
    OMPL_DEBUG("%s: cannot lift %s", getName().c_str(),
               context_.layout().bodies[object].name.c_str());
    context_.world().release();
    query_.checker().hold(std::nullopt);
    return false;
  }
  // Off every corridor found so far if the arm can reach such a place, else off the latest
  // ones only (older corridors may be ways the arm no longer needs).
  const bool carried =
      carryTo(object, placesFor(object, false), ptc) ||
      (corridors_.size() > kRecentCorridors && carryTo(object, placesFor(object, true), ptc));
  // The arm stops before it lets go: path tracking ends at speed, and an object released
  // in motion slides on and may topple.
  const bool stopped = carried && stopHolding(object);
  context_.world().release();
  query_.checker().hold(std::nullopt);
  // Let go in every case: where it was carried, or (not carried) back where it stood.
  const bool settled = holdStill(physics::GripperAction::Release, kSettleSteps);
  return carried && stopped && settled;
}

bool TaskPlanner::carryTo(std::size_t object, const std::vector<Eigen::Vector2d>& places,
                          const Ptc& ptc) {
  const physics::WorldLayout& layout = context_.layout();
  const Eigen::Isometry3d held = layout.linkPose(now().data(), object);
  const Eigen::Isometry3d inGripper = query_.checker().held()->inGripper;
  OMPL_DEBUG("%s: %zu free places for %s", getName().c_str(), places.size(),
             layout.bodies[object].name.c_str());
  // Places the arm cannot reach do not count: the farthest places come first, and near the
  // table's far corners or right under the arm's base many are out of reach.
  std::size_t tried = 0;
  for (std::size_t i = 0;
       i < std::min(places.size(), kReachChecks) && tried < kPlacementsTried && !ptc(); ++i) {
    // Upright as it stood, its centre 5 mm above where it stood on the table.
    const double startHeight =
        physics::WorldLayout::position(context_.startState().data(), object).z();
    Eigen::Isometry3d placed = held;
    placed.translation() = Eigen::Vector3d(places[i].x(), places[i].y(), startHeight + kDropHeight);
    placed.translation().z() +=
        held.translation().z() - physics::WorldLayout::position(now().data(), object).z();
    const physics::PoseTarget target = pose(placed * inGripper.inverse(), 0.005);
    const ompl::base::GoalPtr placeGoal = poseGoal(target);
    if (!reachable(*placeGoal)) {  // out of the arm's reach: not worth a sub-query
      OMPL_DEBUG("%s: place %zu (%.2f, %.2f) out of reach", getName().c_str(), i, places[i].x(),
                 places[i].y());
      continue;
    }
    ++tried;
    const auto path = planTo(placeGoal, ptc);
    if (!path) {
      OMPL_DEBUG("%s: no path to place %zu", getName().c_str(), i);
      continue;
    }
    if (execute(*path, physics::GripperAction::None, -1)) return true;
  }
  return false;
}

bool TaskPlanner::stopHolding(std::size_t object) {
  for (unsigned step = 0; step < kMaxStopSteps; ++step) {
    if (physics::WorldLayout::linearVelocity(now().data(), object).norm() < kRestSpeed) break;
    if (!holdStill(physics::GripperAction::None, 1)) return false;
  }
  return true;
}

bool TaskPlanner::moveAway(std::size_t object, const Ptc& ptc) {
  // An object that could not be moved is passed over for the next one on the way, until
  // some other move changes the scene.
  if (!grasp(object, ptc) || !carryAway(object, ptc)) {
    unmovable_.insert(object);
    return false;
  }
  unmovable_.clear();
  placed_.insert(object);
  ++moves_;
  return true;
}

Footprint TaskPlanner::footprint(std::size_t body) const {
  const Eigen::AlignedBox3d box = context_.layout().bounds(body);
  const Eigen::Vector3d p = physics::WorldLayout::position(now().data(), body);
  return {{p.x(), p.y()}, 0.5 * std::max(box.sizes().x(), box.sizes().y())};
}

std::vector<Eigen::Vector2d> TaskPlanner::placesFor(std::size_t object, bool latestCorridorOnly) {
  PlacementRules rules = placementRules(object);
  // rules.corridors: corridors_, then the disc around the pre-grasp.
  if (latestCorridorOnly && corridors_.size() > kRecentCorridors)
    rules.corridors.erase(rules.corridors.begin(),
                          rules.corridors.end() - static_cast<long>(kRecentCorridors + 1));
  std::vector<Eigen::Vector2d> places =
      samplePlacements(rules, footprint(object).radius, kPlacementDraws, rng_);
  // Within the arm's reach: no farther from its base than the pre-grasp is (plus 10 cm).
  const Eigen::Vector2d base = context_.problem().robot.home.position.head<2>();
  const Eigen::Vector2d goal = context_.goal().position().head<2>();
  const double reach = (goal - base).norm() + 0.1;
  places.erase(std::remove_if(places.begin(), places.end(),
                              [&](const Eigen::Vector2d& p) { return (p - base).norm() > reach; }),
               places.end());
  // Farthest from the pre-grasp first: an object put down near it tends to be in the way of
  // the next path there.
  std::stable_sort(places.begin(), places.end(),
                   [&goal](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
                     return (a - goal).norm() > (b - goal).norm();
                   });
  return places;
}

PlacementRules TaskPlanner::placementRules(std::size_t moved) const {
  const core::Problem& problem = context_.problem();
  PlacementRules rules;
  if (const std::optional<int> support = problem.supportObject()) {
    const Eigen::AlignedBox3d table = core::boundsAtHome(problem.objects.at(*support));
    const Eigen::AlignedBox3d& reach = problem.workspace;
    const double margin = footprint(moved).radius + 0.03;
    rules.area =
        Eigen::AlignedBox2d(Eigen::Vector2d(std::max(table.min().x(), reach.min().x()) + margin,
                                            std::max(table.min().y(), reach.min().y()) + margin),
                            Eigen::Vector2d(std::min(table.max().x(), reach.max().x()) - margin,
                                            std::min(table.max().y(), reach.max().y()) - margin));
  }
  const physics::WorldLayout& layout = context_.layout();
  for (std::size_t b = 0; b < layout.bodies.size(); ++b) {
    if (b == moved || layout.bodies[b].role == physics::BodyRole::Robot) continue;
    Footprint other = footprint(b);
    if (layout.bodies[b].role == physics::BodyRole::Target) other.radius += 0.05;
    rules.occupied.push_back(other);
  }
  // Every way the gripper was found to need so far: an object put on one would be in the way
  // again.
  rules.corridors = corridors_;
  const Eigen::Vector3d goal = context_.goal().position();
  rules.corridors.push_back({Eigen::Vector2d(goal.x(), goal.y())});
  return rules;
}

void TaskPlanner::setObjectMargin() {
  // The same margin for every movable object, all run long; see docs/planners.md.
  if (!settings_.uncertainty) return;
  double sigma = 0.0;
  for (const core::ObjectInstance& object : context_.problem().objects)
    sigma = std::max({sigma, object.uncertainty.x, object.uncertainty.y});
  query_.checker().setObjectMargin(settings_.sigmas * sigma);
}

ompl::base::PlannerStatus TaskPlanner::solve(const Ptc& ptc) {
  checkValidity();
  clear();
  plan_.states.push_back(context_.startState());
  query_.setClearance(settings_.clearance);
  setObjectMargin();
  context_.world().release();
  bool reached = false;
  // Every try moves an object or marks it unmovable; failed tries are bounded too.
  const int maxTries = 3 * settings_.maxMoves + 3;
  for (int attempt = 0; attempt < maxTries && !ptc(); ++attempt) {
    // An object between the fingers at the pre-grasp: no path can reach the goal, so do not
    // spend a sub-query finding out.
    const bool blocked = context_.goal().freeSpaceBlocker(now().data()).has_value();
    // A short try: when the way is clear RRTConnect finds it in a fraction of a second, and
    // the obstruction query below finds the way otherwise.
    constexpr double kDirectTry = 0.5;  // of a sub-query's work
    if (const auto path =
            blocked ? std::nullopt
                    : planTo(query_.problemGoal(true, coordinatesNow()), ptc, kDirectTry)) {
      if (!execute(*path, physics::GripperAction::None, -1)) continue;
      if ((reached = context_.goal().reached(now().data()))) break;
      continue;  // there, but something fills the free space after all: move it next
    }
    if (moves_ == settings_.maxMoves) break;
    clearPath_.reset();
    const std::optional<std::size_t> object = obstruction(ptc);
    if (clearPath_) {
      if (!execute(*clearPath_, physics::GripperAction::None, -1)) continue;
      if ((reached = context_.goal().reached(now().data()))) break;
      continue;
    }
    if (object)
      OMPL_DEBUG("%s: moving %s out of the way", getName().c_str(),
                 context_.layout().bodies[*object].name.c_str());
    if (!object) {
      OMPL_DEBUG("%s: nothing found to move (no path even without movable objects)",
                 getName().c_str());
      break;
    }
    // A move that fails without breaking a rule (no reach, no free place reachable) leaves
    // the scene as it was, or the object put down where it was lifted: try again from there.
    if (!moveAway(*object, ptc) && plan_.violation != physics::Violation::None) {
      OMPL_DEBUG("%s: stopped: %s", getName().c_str(), physics::toString(plan_.violation));
      break;
    }
  }
  context_.world().release();
  if (plan_.controls.empty()) return ompl::base::PlannerStatus::TIMEOUT;
  const double distance = reached ? 0.0 : context_.goal().distance(now().data());
  pdef_->addSolutionPath(physics::controlPath(plan_, context_.spaceInformation()), !reached,
                         distance, getName());
  return reached ? ompl::base::PlannerStatus::EXACT_SOLUTION
                 : ompl::base::PlannerStatus::APPROXIMATE_SOLUTION;
}

}  // namespace kautham::planners::tmp

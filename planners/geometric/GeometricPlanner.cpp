#include "kautham/planners/geometric/GeometricPlanner.h"

#include <ompl/base/PlannerData.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/control/PathControl.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>

#include "kautham/physics/PathTracking.h"
#include "kautham/physics/WorldStateSpace.h"

namespace kautham::planners::geometric {

namespace {

/// The tracked path as OMPL's control path over the context's world states.
std::shared_ptr<ompl::control::PathControl> controlPath(
    const physics::TrackedPath& tracked, const ompl::control::SpaceInformationPtr& si) {
  auto path = std::make_shared<ompl::control::PathControl>(si);
  ompl::base::State* state = si->allocState();
  const auto copy = [&](const std::vector<double>& values) {
    std::copy(values.begin(), values.end(), physics::WorldStateSpace::values(state));
  };
  copy(tracked.states.front());
  path->append(state);
  ompl::control::Control* control = si->allocControl();
  for (std::size_t i = 0; i < tracked.controls.size(); ++i) {
    const physics::ControlStep& step = tracked.controls[i];
    std::copy(step.values.begin(), step.values.end(),
              control->as<ompl::control::RealVectorControlSpace::ControlType>()->values);
    copy(tracked.states[i + 1]);
    path->append(state, control, step.steps * si->getPropagationStepSize());
  }
  si->freeControl(control);
  si->freeState(state);
  return path;
}

}  // namespace

GeometricPlanner::GeometricPlanner(physics::PlanningContext& context, const std::string& name,
                                   const MakeGeometricPlanner& make)
    : Planner(context.spaceInformation(), name),
      context_(context),
      query_(context),
      inner_(make(query_.spaceInformation())) {
  specs_.approximateSolutions = true;
  params_.include(inner_->params());
  declareParam<bool>("simplify", this, &GeometricPlanner::setSimplify, &GeometricPlanner::simplify,
                     "0,1");
  declareParam<double>("speed", this, &GeometricPlanner::setSpeed, &GeometricPlanner::speed,
                       "0.01:1");
  declareParam<double>("clearance", this, &GeometricPlanner::setClearance,
                       &GeometricPlanner::clearance, "0:0.1");
  addPlannerProgressProperty("collision_checks INTEGER",
                             [this] { return std::to_string(query_.checker().checks()); });
  addPlannerProgressProperty("path_waypoints INTEGER",
                             [this] { return std::to_string(waypoints_); });
}

GeometricPlanner::~GeometricPlanner() { freeTreeStates(); }

void GeometricPlanner::freeTreeStates() const {
  for (ompl::base::State* state : treeStates_) si_->freeState(state);
  treeStates_.clear();
}

void GeometricPlanner::clear() {
  Planner::clear();
  inner_->clear();
  freeTreeStates();
}

ompl::base::PlannerStatus GeometricPlanner::solve(
    const ompl::base::PlannerTerminationCondition& ptc) {
  checkValidity();
  query_.setClearance(clearance_);
  const std::optional<CoordinatePath> path =
      query_.plan(query_.joints().start(), query_.problemGoal(), *inner_, ptc, simplify_);
  if (!path) return ompl::base::PlannerStatus::TIMEOUT;
  waypoints_ = path->size();

  physics::TrackingSettings tracking;
  tracking.speed = speed_;
  std::vector<std::vector<double>> joints = query_.jointValues(*path);
  joints.erase(joints.begin());  // the start: where the robot already is
  const physics::TrackedPath tracked =
      physics::trackJointPath(context_, context_.startState(), joints, tracking);

  const double* end = tracked.states.back().data();
  const bool exact = tracked.complete && context_.goal().reached(end);
  const auto& si = context_.spaceInformation();
  pdef_->addSolutionPath(controlPath(tracked, si), !exact,
                         exact ? 0.0 : context_.goal().distance(end), getName());
  return exact ? ompl::base::PlannerStatus::EXACT_SOLUTION
               : ompl::base::PlannerStatus::APPROXIMATE_SOLUTION;
}

void GeometricPlanner::getPlannerData(ompl::base::PlannerData& data) const {
  Planner::getPlannerData(data);
  ompl::base::PlannerData inner(query_.spaceInformation());
  inner_->getPlannerData(inner);
  freeTreeStates();
  auto& checker = const_cast<GeometricQuery&>(query_).checker();
  const unsigned offset = data.numVertices();
  for (unsigned i = 0; i < inner.numVertices(); ++i) {
    const double* c =
        inner.getVertex(i).getState()->as<ompl::base::RealVectorStateSpace::StateType>()->values;
    const std::vector<double> world = checker.stateAt(c);
    ompl::base::State* state = si_->allocState();
    std::copy(world.begin(), world.end(), physics::WorldStateSpace::values(state));
    treeStates_.push_back(state);
    data.addVertex(ompl::base::PlannerDataVertex(state));
  }
  for (unsigned i = 0; i < inner.numVertices(); ++i) {
    std::vector<unsigned> children;
    inner.getEdges(i, children);
    for (unsigned child : children) data.addEdge(offset + i, offset + child);
  }
}

}  // namespace kautham::planners::geometric

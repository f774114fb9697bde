#include "kautham/planners/geometric/GeometricPlanner.h"

#include <ompl/base/PlannerData.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/control/PathControl.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>

#include "kautham/physics/PathTracking.h"
#include "kautham/physics/WorldStateSpace.h"

namespace kautham::planners::geometric {

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
  pdef_->addSolutionPath(physics::controlPath(tracked, si), !exact,
                         exact ? 0.0 : context_.goal().distance(end), getName());
  return exact ? ompl::base::PlannerStatus::EXACT_SOLUTION
               : ompl::base::PlannerStatus::APPROXIMATE_SOLUTION;
}

void GeometricPlanner::getPlannerData(ompl::base::PlannerData& data) const {
  Planner::getPlannerData(data);
  ompl::base::PlannerData inner(query_.spaceInformation());
  inner_->getPlannerData(inner);
  freeTreeStates();
  const physics::SceneChecker& checker = query_.checker();
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

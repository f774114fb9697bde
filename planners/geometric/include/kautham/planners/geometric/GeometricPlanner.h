#pragma once

#include <functional>
#include <string>
#include <vector>

#include <ompl/base/Planner.h>

#include "kautham/planners/geometric/GeometricQuery.h"

namespace kautham::planners::geometric {

/// Makes one of OMPL's geometric planners over a JointSpace's space information.
using MakeGeometricPlanner =
    std::function<ompl::base::PlannerPtr(const ompl::base::SpaceInformationPtr&)>;

/// An OMPL geometric planner (RRTConnect, PRM, ...) as a planner of this framework: it plans a
/// collision-free path over the robot's JointSpace with every object frozen where it starts
/// (no physics), shortcuts it, then drives the robot along it through the physics
/// (physics::trackJointPath), so its plan is a control sequence like every other planner's and
/// replay and validation judge what the physics does with it.
///
/// Its OMPL parameters are the inner planner's, by OMPL's names, plus `simplify`, `speed` and
/// `clearance`.
class GeometricPlanner : public ompl::base::Planner {
 public:
  GeometricPlanner(physics::PlanningContext& context, const std::string& name,
                   const MakeGeometricPlanner& make);
  ~GeometricPlanner() override;

  ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition& ptc) override;
  void clear() override;
  /// The inner planner's graph, each vertex as the world state it stands for.
  void getPlannerData(ompl::base::PlannerData& data) const override;

  bool simplify() const { return simplify_; }
  void setSimplify(bool simplify) { simplify_ = simplify; }
  double speed() const { return speed_; }
  void setSpeed(double speed) { speed_ = speed; }
  double clearance() const { return clearance_; }
  void setClearance(double metres) { clearance_ = metres; }

 private:
  void freeTreeStates() const;

  physics::PlanningContext& context_;
  GeometricQuery query_;
  ompl::base::PlannerPtr inner_;
  bool simplify_ = true;
  double speed_ = 0.5;
  double clearance_ = 0.002;
  std::size_t waypoints_ = 0;
  mutable std::vector<ompl::base::State*> treeStates_;  ///< owned: PlannerData points into them
};

}  // namespace kautham::planners::geometric

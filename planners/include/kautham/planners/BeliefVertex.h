#pragma once

#include <ompl/base/PlannerData.h>

namespace kautham::planners {

/// A planner-data vertex that carries the belief of the motion ending in its state, so the
/// search picture (`kautham view --tree`) can colour p-KPIECE's tree by robustness.
class BeliefVertex : public ompl::base::PlannerDataVertex {
 public:
  BeliefVertex(const ompl::base::State* state, double belief)
      : PlannerDataVertex(state), belief_(belief) {}
  PlannerDataVertex* clone() const override { return new BeliefVertex(*this); }
  double belief() const { return belief_; }

 private:
  double belief_;
};

}  // namespace kautham::planners

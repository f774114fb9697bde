// OMPL's own control planners, run over our physics (ompl::control, not ompl/extensions/ode).

#include <ompl/control/planners/est/EST.h>
#include <ompl/control/planners/kpiece/KPIECE1.h>
#include <ompl/control/planners/pdst/PDST.h>
#include <ompl/control/planners/rrt/RRT.h>
#include <ompl/control/planners/sst/SST.h>

#include "kautham/planners/PlannerRegistry.h"

namespace kautham::planners {

namespace {

using core::ParameterSpec;
using core::ParameterType;

ParameterSpec goalBias(double fallback) {
  return {"goal_bias",
          ParameterType::Real,
          fallback,
          0.0,
          1.0,
          "probability of expanding towards the goal instead of exploring",
          {"Goal Bias", "goalBias"}};
}

PlannerRegistry::Entry kpiece() {
  return {"KPIECE",
          "OMPL's KPIECE1 over ODE: grid of end-effector cells, expands from the exterior cells",
          {goalBias(0.05),
           {"border_fraction",
            ParameterType::Real,
            0.8,
            0.0,
            1.0,
            "fraction of expansions from exterior (border) cells",
            {"Border Fraction"}},
           {"max_close_samples",
            ParameterType::Integer,
            30,
            1,
            10000,
            "how many motions closest to the goal are kept for goal-biased expansion",
            {}},
           {"cell_size",
            ParameterType::Real,
            0.05,
            0.001,
            1.0,
            "projection cell side, as a fraction of the workspace side",
            {"Cell Size"}}},
          [](const core::ParameterSet& p, physics::PlanningContext& context) {
            context.projection().setCellFraction(p.real("cell_size"));
            auto planner = std::make_shared<ompl::control::KPIECE1>(context.spaceInformation());
            planner->setGoalBias(p.real("goal_bias"));
            planner->setBorderFraction(p.real("border_fraction"));
            planner->setMaxCloseSamplesCount(static_cast<unsigned>(p.integer("max_close_samples")));
            return ompl::base::PlannerPtr(planner);
          }};
}

PlannerRegistry::Entry rrt() {
  return {"RRT",
          "OMPL's control RRT over ODE: grows towards random end-effector positions",
          {goalBias(0.05),
           {"intermediate_states",
            ParameterType::Boolean,
            0,
            0,
            1,
            "add the states inside each motion to the tree",
            {}}},
          [](const core::ParameterSet& p, physics::PlanningContext& context) {
            auto planner = std::make_shared<ompl::control::RRT>(context.spaceInformation());
            planner->setGoalBias(p.real("goal_bias"));
            planner->setIntermediateStates(p.boolean("intermediate_states"));
            return ompl::base::PlannerPtr(planner);
          }};
}

PlannerRegistry::Entry sst() {
  return {"SST",
          "OMPL's Stable Sparse RRT over ODE: keeps the best-cost node in each neighbourhood",
          {goalBias(0.05),
           {"selection_radius",
            ParameterType::Real,
            0.2,
            0.0,
            100.0,
            "m of end-effector distance within which the best node is expanded",
            {}},
           {"pruning_radius",
            ParameterType::Real,
            0.1,
            0.0,
            100.0,
            "m of end-effector distance that one witness covers",
            {}}},
          [](const core::ParameterSet& p, physics::PlanningContext& context) {
            auto planner = std::make_shared<ompl::control::SST>(context.spaceInformation());
            planner->setGoalBias(p.real("goal_bias"));
            planner->setSelectionRadius(p.real("selection_radius"));
            planner->setPruningRadius(p.real("pruning_radius"));
            return ompl::base::PlannerPtr(planner);
          }};
}

PlannerRegistry::Entry est() {
  return {"EST",
          "OMPL's control EST over ODE: expands from sparsely covered end-effector cells",
          {goalBias(0.05),
           {"range",
            ParameterType::Real,
            0.0,
            0.0,
            100.0,
            "longest motion a sampled target may ask for (0: OMPL's default)",
            {}}},
          [](const core::ParameterSet& p, physics::PlanningContext& context) {
            auto planner = std::make_shared<ompl::control::EST>(context.spaceInformation());
            planner->setGoalBias(p.real("goal_bias"));
            if (p.real("range") > 0.0) planner->setRange(p.real("range"));
            return ompl::base::PlannerPtr(planner);
          }};
}

PlannerRegistry::Entry pdst() {
  return {"PDST",
          "OMPL's Path-Directed Subdivision Tree over ODE: subdivides the end-effector space",
          {goalBias(0.05)},
          [](const core::ParameterSet& p, physics::PlanningContext& context) {
            auto planner = std::make_shared<ompl::control::PDST>(context.spaceInformation());
            planner->setGoalBias(p.real("goal_bias"));
            return ompl::base::PlannerPtr(planner);
          }};
}

}  // namespace

void registerOmplControlPlanners(PlannerRegistry& registry) {
  registry.add(kpiece());
  registry.add(rrt());
  registry.add(sst());
  registry.add(est());
  registry.add(pdst());
}

}  // namespace kautham::planners

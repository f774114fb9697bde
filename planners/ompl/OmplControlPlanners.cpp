// OMPL's own control planners, run over our physics (ompl::control, not ompl/extensions/ode),
// and o-KPIECE, the paper's baseline: OMPL's KPIECE1 whose validity checks only the knowledge
// rules.
// Each parameter is OMPL's, by OMPL's name: our spec gives its default, range, description and
// Kautham's alias, and the value is set through OMPL's parameter set (omplPlannerEntry).

#include <ompl/control/planners/est/EST.h>
#include <ompl/control/planners/kpiece/KPIECE1.h>
#include <ompl/control/planners/pdst/PDST.h>
#include <ompl/control/planners/rrt/RRT.h>
#include <ompl/control/planners/sst/SST.h>

#include "kautham/planners/PlannerEntry.h"

namespace kautham::planners {

namespace {

using core::Parameter;

PlannerRegistry::Entry kpiece() {
  return omplPlannerEntry<ompl::control::KPIECE1>(
      "KPIECE",
      "OMPL's KPIECE1 over ODE: grid of end-effector cells, expands from the exterior cells",
      {goalBiasParameter(0.05),
       Parameter::real("border_fraction")
           .byDefault(0.8)
           .range(0.0, 1.0)
           .describe("fraction of expansions from exterior (border) cells")
           .alias("Border Fraction"),
       Parameter::integer("max_close_samples")
           .byDefault(30)
           .range(1, 10000)
           .describe("how many motions closest to the goal are kept for goal-biased expansion"),
       cellSizeParameter()});
}

PlannerRegistry::Entry rrt() {
  return omplPlannerEntry<ompl::control::RRT>(
      "RRT", "OMPL's control RRT over ODE: grows towards random end-effector positions",
      {goalBiasParameter(0.05), Parameter::flag("intermediate_states")
                                    .byDefault(0)
                                    .describe("add the states inside each motion to the tree")});
}

PlannerRegistry::Entry sst() {
  return omplPlannerEntry<ompl::control::SST>(
      "SST", "OMPL's Stable Sparse RRT over ODE: keeps the best-cost node in each neighbourhood",
      {goalBiasParameter(0.05),
       Parameter::real("selection_radius")
           .byDefault(0.2)
           .range(0.0, 100.0)
           .describe("m of end-effector distance (with a configuration goal: of joint distance, m "
                     "and rad) within which the best node is expanded")
           .alias("SelectionRadius"),
       Parameter::real("pruning_radius")
           .byDefault(0.1)
           .range(0.0, 100.0)
           .describe("m of end-effector distance (with a configuration goal: of joint distance, m "
                     "and rad) that one witness covers")
           .alias("PruningRadius")});
}

PlannerRegistry::Entry est() {
  return omplPlannerEntry<ompl::control::EST>(
      "EST", "OMPL's control EST over ODE: expands from sparsely covered end-effector cells",
      {goalBiasParameter(0.05),
       Parameter::real("range")
           .byDefault(0.0)
           .range(0.0, 100.0)
           .describe("longest motion a sampled target may ask for (0: OMPL's default)")});
}

PlannerRegistry::Entry pdst() {
  return omplPlannerEntry<ompl::control::PDST>(
      "PDST", "OMPL's Path-Directed Subdivision Tree over ODE: subdivides the end-effector space",
      {goalBiasParameter(0.05)});
}

PlannerRegistry::Entry oKpiece() {
  return omplPlannerEntry<ompl::control::KPIECE1>(
      "o-KPIECE",
      "the paper's baseline: KPIECE whose validity knows only whom the robot may touch "
      "(no after-effect checks, no uncertainty)",
      {goalBiasParameter(0.05), cellSizeParameter()}, [](physics::PlanningContext& context) {
        context.usePlanningRules(physics::ValidityRules::KnowledgeOnly);
      });
}

}  // namespace

void registerOmplControlPlanners(PlannerRegistry& registry) {
  registry.add(kpiece());
  registry.add(rrt());
  registry.add(sst());
  registry.add(est());
  registry.add(pdst());
  registry.add(oKpiece());
}

}  // namespace kautham::planners

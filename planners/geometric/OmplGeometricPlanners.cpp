// OMPL's geometric planners over the robot's configuration space (JointSpace coordinates),
// collision-checked against the frozen scene, their paths then driven through the physics
// (GeometricPlanner). Each parameter is OMPL's, by OMPL's name, with Kautham's alias.
// Two names are taken by the control planners over ODE (RRT, KPIECE), so the geometric ones
// are RRT-geometric and KPIECE-geometric; Kautham's omplRRT and omplKPIECE map onto those.

#include <ompl/geometric/planners/est/EST.h>
#include <ompl/geometric/planners/informedtrees/BITstar.h>
#include <ompl/geometric/planners/kpiece/KPIECE1.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>

#include "kautham/planners/PlannerEntry.h"
#include "kautham/planners/geometric/ComponentPRM.h"
#include "kautham/planners/geometric/GeometricPlanner.h"
#include "kautham/planners/geometric/LinearLazyRRT.h"

namespace kautham::planners {

namespace {

using core::Parameter;
using core::ParameterSpec;

Parameter range() {
  return Parameter::real("range")
      .byDefault(0.0)
      .range(0.0, 10.0)
      .describe(
          "longest motion added to the tree, in configuration coordinates (0: OMPL's "
          "default, a fifth of the space's extent)")
      .alias("Range");
}

/// The parameters every geometric planner has besides OMPL's own.
std::vector<ParameterSpec> withTracking(std::vector<Parameter> own) {
  own.push_back(Parameter::flag("simplify")
                    .byDefault(1)
                    .describe("shortcut the path (OMPL's PathSimplifier, at most 1 s)")
                    .alias("Simplify Solution"));
  own.push_back(Parameter::real("speed")
                    .byDefault(0.5)
                    .range(0.01, 1.0)
                    .describe("joint speed along the path, as a fraction of each joint's "
                              "velocity limit")
                    .alias("Speed"));
  own.push_back(Parameter::real("clearance")
                    .byDefault(0.002)
                    .range(0.0, 0.1)
                    .describe("m the robot keeps from every obstacle while planning, so that "
                              "the physics, which tracks the path only closely, does not graze "
                              "one"));
  std::vector<ParameterSpec> specs;
  for (const Parameter& p : own) specs.push_back(p.spec());
  return specs;
}

template <typename OmplPlanner>
PlannerRegistry::Entry geometricEntry(std::string name, std::string summary,
                                      std::vector<Parameter> parameters) {
  return {name, std::move(summary), withTracking(std::move(parameters)),
          [name](const core::ParameterSet& values, physics::PlanningContext& context) {
            auto planner = std::make_shared<geometric::GeometricPlanner>(
                context, name, [](const ompl::base::SpaceInformationPtr& si) {
                  return std::make_shared<OmplPlanner>(si);
                });
            setOmplParameters(*planner, values);
            return ompl::base::PlannerPtr(planner);
          }};
}

}  // namespace

void registerOmplGeometricPlanners(PlannerRegistry& registry) {
  registry.add(geometricEntry<ompl::geometric::RRTConnect>(
      "RRTConnect", "geometric: OMPL's bidirectional RRT (no physics while planning)",
      {range(), Parameter::flag("intermediate_states")
                    .byDefault(0)
                    .describe("add the states along each motion to the trees")}));
  registry.add(geometricEntry<ompl::geometric::RRT>(
      "RRT-geometric", "geometric: OMPL's RRT (no physics while planning)",
      {range(), goalBiasParameter(0.05)}));
  registry.add(geometricEntry<ompl::geometric::RRTstar>(
      "RRTstar", "geometric: OMPL's RRT*, asymptotically optimal; stops at its first path here",
      {range(), goalBiasParameter(0.05),
       Parameter::real("rewire_factor")
           .byDefault(1.1)
           .range(1.0, 10.0)
           .describe("scales the rewiring radius (or k) over its theoretical minimum")}));
  registry.add(geometricEntry<ompl::geometric::BITstar>(
      "BITstar",
      "geometric: OMPL's Batch Informed Trees, asymptotically optimal; stops at its first path",
      {Parameter::integer("samples_per_batch")
           .byDefault(100)
           .range(1, 1000000)
           .describe("samples added to the graph in each batch")}));
  registry.add(geometricEntry<geometric::ComponentPRM>(
      "PRM",
      "geometric: OMPL's probabilistic roadmap, edges only between its components, as Kautham's "
      "omplPRM (no physics while planning)",
      {Parameter::integer("max_nearest_neighbors")
           .byDefault(10)
           .range(1, 1000)
           .describe("neighbours each new roadmap vertex tries to connect to")
           .alias("MaxNearestNeighbors")}));
  registry.add(geometricEntry<geometric::LinearLazyRRT>(
      "LazyRRT", "geometric: OMPL's lazy RRT, collision checks postponed to candidate paths",
      {range(), goalBiasParameter(0.05)}));
  registry.add(geometricEntry<ompl::geometric::KPIECE1>(
      "KPIECE-geometric", "geometric: OMPL's KPIECE1 over configuration coordinates",
      {range(), goalBiasParameter(0.05),
       Parameter::real("border_fraction")
           .byDefault(0.9)
           .range(0.0, 1.0)
           .describe("fraction of expansions from exterior (border) cells")
           .alias("Border Fraction")}));
  registry.add(geometricEntry<ompl::geometric::EST>("EST-geometric",
                                                    "geometric: OMPL's expansive space trees",
                                                    {range(), goalBiasParameter(0.5)}));
}

}  // namespace kautham::planners

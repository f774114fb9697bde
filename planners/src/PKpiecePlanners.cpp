// The KPIECE family of the paper: p-KPIECE (ours, on OMPL's grid) and o-KPIECE (OMPL's
// KPIECE1 with the knowledge rules only).

#include <ompl/control/planners/kpiece/KPIECE1.h>

#include "kautham/planners/PKpiece.h"
#include "kautham/planners/PlannerRegistry.h"

namespace kautham::planners {

namespace {

using core::ParameterSpec;
using core::ParameterType;

ParameterSpec cellSize() {
  return {"cell_size",  ParameterType::Real,
          0.05,         0.001,
          1.0,          "projection cell side, as a fraction of the workspace side",
          {"Cell Size"}};
}

ParameterSpec goalBias(double byDefault) {
  return {"goal_bias",
          ParameterType::Real,
          byDefault,
          0.0,
          1.0,
          "probability of expanding one of the motions nearest the goal",
          {"Goal Bias", "goalBias"}};
}

PlannerRegistry::Entry pKpiece() {
  return {"p-KPIECE",
          "the paper's planner: keeps the most robust of k candidates, judged by n_p particles "
          "under pose, contact and control uncertainty",
          {{"candidates",
            ParameterType::Integer,
            5,
            1,
            1000,
            "k: candidate motions sampled per expansion",
            {"k"}},
           {"particles",
            ParameterType::Integer,
            15,
            1,
            10000,
            "n_p: particle motions that judge each valid candidate",
            {"n_p", "np"}},
           {"displacement",
            ParameterType::Real,
            0.0,
            0.0,
            100.0,
            "d: most an object may move in one motion (m); 0: the problem's maxDisplacement",
            {"d"}},
           {"random_candidate",
            ParameterType::Real,
            0.05,
            0.0,
            1.0,
            "bias: probability of keeping a random valid candidate instead of the best",
            {"bias"}},
           {"belief_weight",
            ParameterType::Real,
            0.0,
            0.0,
            1e9,
            "f: weight of the cell belief in the importance; 0: the number of cells",
            {"f"}},
           {"kpiece_selection",
            ParameterType::Real,
            0.1,
            0.0,
            1.0,
            "probability of choosing a cell's motion as KPIECE does instead of by belief",
            {}},
           {"uncertainty",
            ParameterType::Boolean,
            1,
            0,
            1,
            "sample poses, contacts and control noise (0: one nominal particle, the paper's pKP)",
            {}},
           {"goal_confidence",
            ParameterType::Real,
            0.5,
            0.0,
            1.0,
            "estimated success a plan needs to end the search: the path belief times the "
            "fraction of the last candidate's particles that end valid in the goal",
            {}},
           {"path_belief",
            ParameterType::Boolean,
            1,
            0,
            1,
            "judge cells and motions by the belief of the whole path to them (0: by the "
            "motion's own)",
            {}},
           {"robot_spread",
            ParameterType::Boolean,
            1,
            0,
            1,
            "particles start from the robot states their parent's particles reached, so "
            "control noise accumulates along a path (0: from the tree's robot state)",
            {}},
           {"prune_candidates",
            ParameterType::Boolean,
            1,
            0,
            1,
            "stop judging a candidate once it cannot beat the best so far (the same choice, "
            "less work)",
            {}},
           {"goal_steering",
            ParameterType::Boolean,
            1,
            0,
            1,
            "in a goal-biased expansion, aim one candidate at the goal (a numerical Jacobian "
            "from probe steps)",
            {}},
           // Measured on kuka_cans_10: 0.2 solves more seeds, with shorter plans, than 0.05.
           goalBias(0.2),
           {"border_fraction",
            ParameterType::Real,
            0.8,
            0.0,
            1.0,
            "probability of expanding an exterior cell",
            {"Border Fraction"}},
           cellSize()},
          [](const core::ParameterSet& p, physics::PlanningContext& context) {
            context.projection().setCellFraction(p.real("cell_size"));
            PKpieceSettings settings;
            settings.candidates = static_cast<unsigned>(p.integer("candidates"));
            settings.particles = static_cast<unsigned>(p.integer("particles"));
            settings.displacement = p.real("displacement") > 0.0
                                        ? p.real("displacement")
                                        : context.problem().interaction.maxDisplacement;
            settings.randomCandidate = p.real("random_candidate");
            settings.beliefWeight = p.real("belief_weight");
            settings.kpieceSelection = p.real("kpiece_selection");
            settings.uncertainty = p.boolean("uncertainty");
            settings.goalBias = p.real("goal_bias");
            settings.goalConfidence = p.real("goal_confidence");
            settings.pathBelief = p.boolean("path_belief");
            settings.robotSpread = p.boolean("robot_spread");
            settings.pruneCandidates = p.boolean("prune_candidates");
            settings.goalSteering = p.boolean("goal_steering");
            settings.borderFraction = p.real("border_fraction");
            return ompl::base::PlannerPtr(std::make_shared<PKpiece>(context, settings));
          }};
}

PlannerRegistry::Entry oKpiece() {
  return {"o-KPIECE",
          "the paper's baseline: KPIECE whose validity knows only whom the robot may touch "
          "(no after-effect checks, no uncertainty)",
          {goalBias(0.05), cellSize()},
          [](const core::ParameterSet& p, physics::PlanningContext& context) {
            context.usePlanningRules(physics::ValidityRules::KnowledgeOnly);
            context.projection().setCellFraction(p.real("cell_size"));
            auto planner = std::make_shared<ompl::control::KPIECE1>(context.spaceInformation());
            planner->setName("o-KPIECE");
            planner->setGoalBias(p.real("goal_bias"));
            return ompl::base::PlannerPtr(planner);
          }};
}

}  // namespace

void registerKpieceFamily(PlannerRegistry& registry) {
  registry.add(pKpiece());
  registry.add(oKpiece());
}

}  // namespace kautham::planners

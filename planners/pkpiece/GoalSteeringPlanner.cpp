// goal-steering: p-KPIECE's goal steering followed motion by motion from the start, without any
// search (ours, a diagnosis). What the steering alone does in a scene, and the first rule it
// breaks there, is what decides where p-KPIECE's goal-biased trees get stuck: sessions 44 and
// 59 followed it by hand to find which push tipped which can (docs/planners.md, "The goal
// steering alone").

#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <ompl/base/Planner.h>
#include <ompl/control/PathControl.h>
#include <ompl/control/SpaceInformation.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>
#include <ompl/util/RandomNumbers.h>

#include "kautham/physics/WorldStateSpace.h"
#include "kautham/planners/FailureReporter.h"
#include "kautham/planners/PlannerEntry.h"
#include "kautham/planners/pkpiece/FailureTally.h"
#include "kautham/planners/pkpiece/GoalSteering.h"
#include "kautham/planners/pkpiece/MotionEvaluator.h"
#include "kautham/planners/pkpiece/PKpieceSettings.h"

namespace kautham::planners {

namespace {

// The most motions followed: on the dense suite the steering ends within 36, through every
// clearing push.
constexpr unsigned kMostMotions = 300;
// The steering has stalled when this many motions in a row came no nearer by its own measure
// (GoalSteering::rankDistance): it keeps steering into whatever holds the arm up.
constexpr unsigned kStallMotions = 20;
constexpr double kNearer = 0.001;  // m

/// p-KPIECE's parameters, and which of its trees to steer for.
struct GoalSteeringSettings {
  PKpieceSettings pkpiece;
  /// With push_angle_spread, the tree whose pushes are followed (ClearingPush::setTree): the
  /// steering of p-KPIECE's tree of that number, at the angles that tree pushes at.
  unsigned tree;

  static core::SettingsParameters<GoalSteeringSettings> parameters() {
    return core::SettingsParameters<GoalSteeringSettings>()
        .include(&GoalSteeringSettings::pkpiece, PKpieceSettings::parameters())
        .add(&GoalSteeringSettings::tree,
             core::Parameter::integer("tree").byDefault(0).range(0, 100000).describe(
                 "follow the steering of p-KPIECE's tree of this number: with "
                 "push_angle_spread, the trees from push_angle_after on push at "
                 "angles of their own (0: the first tree's, straight across)"));
  }
};

/// Follows the goal steering from the start: one motion after another, each run in the nominal
/// physics as p-KPIECE runs its candidates, until one ends deep enough in the goal region
/// (goal_margin), breaks a rule, the steering has no motion to give or stalls. The motions
/// that stayed valid are the plan (approximate unless it reached the goal); the rule broken,
/// and by which object, is its one candidate failure.
class GoalSteeringPlanner : public ompl::base::Planner, public FailureReporter {
  enum class Stop { None, Goal, RuleBroken, NoMotion, Stalled };

 public:
  GoalSteeringPlanner(physics::PlanningContext& context, const GoalSteeringSettings& chosen)
      : Planner(context.spaceInformation(), "goal-steering"),
        context_(context),
        settings_(chosen.pkpiece),
        evaluator_(context, settings_.displacement),  // only particles judge the displacement
        steering_(context, evaluator_, settings_.clearingPush,
                  pushSettingsOf(settings_, ompl::RNG::getSeed()), settings_.kinematicSteering,
                  approachSettingsOf(settings_)) {
    // A learned tree's angles come from the trees p-KPIECE grew before it, which are not here.
    if (const std::uint64_t before = steering_.pushAngles().treesBefore(chosen.tree))
      throw std::invalid_argument(
          "goal-steering: tree " + std::to_string(chosen.tree) +
          " pushes at angles learned from p-KPIECE's trees before it (push_angle_generation), "
          "which goal-steering does not grow: follow a tree below " +
          std::to_string(before) + ", or set push_angle_generation=0");
    steering_.setTree(chosen.tree);
    specs_.approximateSolutions = true;
    evaluator_.setNominalMargins(settings_.tiltMargin, settings_.targetMargin);
    addPlannerProgressProperty("motions INTEGER", [this] { return std::to_string(motions_); });
    // Why the following ended, unless at the goal or at a broken rule (the candidate failure):
    // the steering had no motion to give, or it stalled (or used up its motions).
    addPlannerProgressProperty("no_motion BOOLEAN",
                               [this] { return std::to_string(int(stop_ == Stop::NoMotion)); });
    addPlannerProgressProperty("stalled BOOLEAN",
                               [this] { return std::to_string(int(stop_ == Stop::Stalled)); });
  }

  ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition& ptc) override {
    checkValidity();
    clearRun();
    const std::size_t stateSize = context_.layout().stateSize();
    const double* start = physics::WorldStateSpace::values(pdef_->getStartState(0));
    std::vector<double> state(start, start + stateSize);
    double best = steering_.rankDistance(state.data());
    unsigned stalled = 0;
    while (!ptc && motions_ < kMostMotions) {
      const std::optional<NominalMotion> motion = steering_.towardsGoal(state.data());
      if (!motion) return finish(Stop::NoMotion);
      NominalRun run = evaluator_.runNominal(state.data(), motion->control.data(), motion->steps,
                                             /*throughGoal=*/true);
      ++motions_;
      const bool atGoal = run.reachedGoal && cutDeepEnough(run);
      append(motion->control, run);
      if (atGoal) return finish(Stop::Goal);
      if (run.stoppedBy != physics::Violation::None) {
        failures_.addViolation(run.stoppedBy, run.stoppedOn);
        return finish(Stop::RuleBroken);
      }
      state = run.end;
      const double rank = steering_.rankDistance(state.data());
      stalled = rank < best - kNearer ? 0 : stalled + 1;
      best = std::min(best, rank);
      if (stalled >= kStallMotions) return finish(Stop::Stalled);
    }
    return finish(motions_ < kMostMotions ? Stop::None : Stop::Stalled);  // None: the time ran out
  }

  void clear() override {
    Planner::clear();
    clearRun();
  }

  void getPlannerData(ompl::base::PlannerData& data) const override {
    Planner::getPlannerData(data);
    if (!path_) return;
    const auto& states = path_->getStates();
    data.addStartVertex(ompl::base::PlannerDataVertex(states.front()));
    for (std::size_t i = 1; i < states.size(); ++i)
      data.addEdge(ompl::base::PlannerDataVertex(states[i - 1]),
                   ompl::base::PlannerDataVertex(states[i]));
  }

  std::vector<FailureCount> sampledFailures() const override { return {}; }
  std::vector<FailureCount> candidateFailures() const override {
    return failures_.counts(context_.layout());
  }
  std::vector<FailureCount> steeredFailures() const override { return candidateFailures(); }

 private:
  void clearRun() {
    path_.reset();
    motions_ = 0;
    stop_ = Stop::None;
    failures_ = FailureTally();
  }

  /// Ends the run where it first gets deep enough into the goal region (goal_margin), as
  /// p-KPIECE's plans end; false if it never does.
  bool cutDeepEnough(NominalRun& run) const {
    const physics::GoalSpec& spec = context_.goal().spec();
    const double deepEnough =
        settings_.goalMargin * (spec.joints.empty() ? spec.tolerance : spec.jointTolerance);
    for (unsigned step = run.goalFrom; step <= run.steps; ++step)
      if (context_.goal().distance(run.states[step - 1].data()) <= deepEnough) {
        run.states.resize(step);
        run.steps = step;
        run.end = run.states.back();
        return true;
      }
    return false;
  }

  /// Adds the valid part of a run to the plan (nothing if it broke a rule at its first step).
  void append(const std::vector<double>& control, const NominalRun& run) {
    auto* csi = static_cast<ompl::control::SpaceInformation*>(si_.get());
    if (!path_) {
      path_ = std::make_shared<ompl::control::PathControl>(si_);
      path_->append(pdef_->getStartState(0));
    }
    if (run.steps == 0) return;
    ompl::base::State* end = si_->allocState();
    std::copy(run.end.begin(), run.end.end(), physics::WorldStateSpace::values(end));
    ompl::control::Control* c = csi->allocControl();
    std::copy(control.begin(), control.end(),
              c->as<ompl::control::RealVectorControlSpace::ControlType>()->values);
    path_->append(end, c, run.steps * csi->getPropagationStepSize());
    csi->freeControl(c);
    si_->freeState(end);
  }

  ompl::base::PlannerStatus finish(Stop stop) {
    stop_ = stop;
    if (!path_ || path_->getControlCount() == 0) return ompl::base::PlannerStatus::TIMEOUT;
    const bool exact = stop == Stop::Goal;
    const double distance =
        context_.goal().distance(physics::WorldStateSpace::values(path_->getStates().back()));
    pdef_->addSolutionPath(path_, !exact, distance, getName());
    return exact ? ompl::base::PlannerStatus::EXACT_SOLUTION
                 : ompl::base::PlannerStatus::APPROXIMATE_SOLUTION;
  }

  physics::PlanningContext& context_;
  PKpieceSettings settings_;
  MotionEvaluator evaluator_;
  GoalSteering steering_;
  std::shared_ptr<ompl::control::PathControl> path_;
  unsigned motions_ = 0;
  Stop stop_ = Stop::None;
  FailureTally failures_;
};

}  // namespace

void registerGoalSteering(PlannerRegistry& registry) {
  registry.add(plannerEntry<GoalSteeringSettings>(
      "goal-steering",
      "p-KPIECE's goal steering followed from the start motion by motion, without a search: "
      "what the steering alone does, and the first rule it breaks (a diagnosis; p-KPIECE's "
      "parameters, of which the steering's count, and the tree whose steering to follow)",
      GoalSteeringSettings::parameters(),
      [](const GoalSteeringSettings& settings, physics::PlanningContext& context) {
        return ompl::base::PlannerPtr(std::make_shared<GoalSteeringPlanner>(context, settings));
      }));
}

}  // namespace kautham::planners

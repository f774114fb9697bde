#pragma once

#include <array>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <vector>

#include <ompl/base/Planner.h>
#include <ompl/datastructures/GridB.h>
#include <ompl/util/RandomNumbers.h>

#include "kautham/physics/PlanningContext.h"
#include "kautham/planners/BeliefReporter.h"
#include "kautham/planners/DeadlinePlanner.h"
#include "kautham/planners/FailureReporter.h"
#include "kautham/planners/ParallelPlanner.h"
#include "kautham/planners/pkpiece/GoalSteering.h"
#include "kautham/planners/pkpiece/MotionEvaluator.h"
#include "kautham/planners/pkpiece/ObjectPoseBelief.h"
#include "kautham/planners/pkpiece/PKpieceSettings.h"
#include "kautham/planners/pkpiece/PlanVerifier.h"
#include "kautham/planners/pkpiece/RobotSpread.h"
#include "kautham/planners/pkpiece/TreeProcesses.h"

namespace kautham::planners {

/// p-KPIECE (Muhayyuddin, Moll, Kavraki, Rosell, RA-L 2018; Algorithms 1 and 2): KPIECE whose
/// expansions keep the most robust of k candidate motions, judged by n_p particle motions run
/// under sampled object poses, contact parameters and control noise, and whose cell and motion
/// choices prefer robust regions. Built on OMPL's GridB, not on KPIECE1 (whose selection code
/// cannot be overridden). Each motion stores its end state, its control and duration, its
/// belief and the pose distribution of the objects at its end (ObjectPoseBelief).
class PKpiece : public ompl::base::Planner,
                public BeliefReporter,
                public FailureReporter,
                public ParallelPlanner,
                public DeadlinePlanner {
 public:
  PKpiece(physics::PlanningContext& context, const PKpieceSettings& settings);
  ~PKpiece() override;

  ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition& ptc) override;
  void clear() override;
  void getPlannerData(ompl::base::PlannerData& data) const override;
  std::vector<double> solutionBeliefs() const override { return solutionBeliefs_; }
  std::vector<FailureCount> sampledFailures() const override {
    return evaluator_.particleFailures().counts(context_.layout());
  }
  std::vector<FailureCount> candidateFailures() const override {
    return candidateFailures_.counts(context_.layout());
  }
  std::vector<FailureCount> steeredFailures() const override {
    return steeredFailures_.counts(context_.layout());
  }
  /// Particle motions run in threads - 1 worker processes and this one (MotionEvaluator).
  /// The processes the search uses: particle workers, or with parallel_trees the trees grown
  /// at once (each in a process of its own, its particles and verifications run there).
  void setThreads(unsigned threads) override;
  /// Plan verification stops there (PlanVerifier::stopAt), and so does the search; clear()
  /// forgets it.
  void setDeadline(Clock::time_point deadline) override;

 private:
  struct Motion;
  struct CellData;
  struct ByImportance {
    bool operator()(const CellData* a, const CellData* b) const;
  };
  using Grid = ompl::GridB<CellData*, ByImportance>;
  struct Candidate;

  void addMotion(Motion* motion);
  /// Adds a candidate's nominal run to candidateFailures() (and steeredFailures()) if it
  /// stopped at a broken rule.
  void tallyBrokenRule(const NominalRun& run, bool steered);
  /// Adds `motion` to a list of the motions nearest the goal, nearest first, kept short.
  static void keepIfNear(std::vector<Motion*>& nearest, Motion* motion);
  /// Whether a plan could end after `motion` (its path belief reaches goalConfidence): the goal
  /// bias expands only from such motions.
  bool mayEndAPlan(const Motion& motion) const;
  Motion* selectMotion();
  Motion* selectInCell(const CellData& cell);
  Motion* nearGoalMotion();
  /// Grows the tree from `from`; returns the last motion added, or null.
  Motion* expand(Motion* from);
  Motion* addPiece(Motion* parent, const Candidate& chosen, const std::vector<double>& end,
                   unsigned steps, double fromPathBelief,
                   std::shared_ptr<const ObjectPoseBelief> poses,
                   std::shared_ptr<const RobotSpread> robotSpread);
  /// The objects' pose distribution after `step` steps of the chosen candidate, fitted to
  /// where its nominal run and its particles (those valid so far) had them then.
  std::shared_ptr<const ObjectPoseBelief> posesAfter(const Candidate& chosen, unsigned step,
                                                     const Motion& from);
  /// Steps after which a nominal run is cut into tree motions: where the end effector
  /// changes cell, and at the end.
  std::vector<unsigned> pieceEnds(const NominalRun& run) const;
  /// The robot states the chosen candidate's particles reached after `step` steps, with the
  /// objects the path has disturbed (objectSpread); the parent motion's spread if none got
  /// that far.
  std::shared_ptr<const RobotSpread> robotSpreadAt(const Candidate& chosen, unsigned step,
                                                   const Motion& from) const;
  /// The chosen candidate's particles still valid after `step` steps (a recorded step of the
  /// candidate), by index, and the states they had then.
  static std::vector<std::size_t> particlesAt(const Candidate& chosen, unsigned step);
  static std::vector<const std::vector<double>*> particleStatesAt(const Candidate& chosen,
                                                                  unsigned step);
  /// An object body the spread must carry (objectSpread): the nominal run moved it from
  /// `start`, or a particle still has it moving.
  static bool disturbed(std::size_t body, const double* start, const double* nominal,
                        const std::vector<const std::vector<double>*>& particles);
  /// Candidates are judged by particles (uncertainty on), not by their nominal run alone.
  bool withParticles() const;
  /// Where the particles' states after `step` steps are in their recorded states.
  static std::size_t recordIndex(const Candidate& candidate, unsigned step);
  /// Ends a goal-reaching candidate at the step where most of its particles are in the goal,
  /// of equals (always, without particles) where its nominal run is nearest the goal point,
  /// among the steps within deepEnoughDistance() of the goal point (getsDeepEnough holds).
  void settleInGoal(Candidate& candidate) const;
  /// Whether a run through the goal comes within deepEnoughDistance() at some step.
  bool getsDeepEnough(const NominalRun& run) const;
  /// How near the goal point a plan may end: goal_margin times the goal's tolerance.
  double deepEnoughDistance() const;
  /// The belief cells and motion choice use: the path's or the motion's own (pathBelief).
  double selectionBelief(const Motion& motion) const;
  Grid::Coord cellOf(const std::vector<double>& state) const;
  bool objectsMoved(const double* start, const double* state) const;
  /// The k candidates of one expansion: drawn together, their nominal runs made in order as
  /// the choice asks for them (lazyCandidates), or all at once.
  struct CandidateDraw {
    std::vector<NominalMotion> motions;
    bool steered = false;          ///< motions[0] is aimed by GoalSteering
    std::size_t ran = 0;           ///< motions[0, ran) have had their nominal runs
    std::vector<Candidate> valid;  ///< of those, the ones valid from their first step, in order
  };
  /// Draws an expansion's k candidates from `from` (none run yet).
  CandidateDraw drawCandidates(const Motion& from);
  /// Makes the nominal runs of draw's motions up to `upTo` (together, over the worker
  /// processes) and admits the valid ones.
  void runCandidates(CandidateDraw& draw, const Motion& from, std::size_t upTo);
  /// A candidate made of a valid nominal run, ready to be judged.
  Candidate admit(const std::vector<double>& control, NominalRun&& run, bool steered,
                  const Motion& from);
  /// Runs the candidate's particles (or judges its nominal run), pruned against `toBeat`.
  void judge(Candidate& candidate, const Motion& from, double toBeat);
  /// Judges the kept candidate again, in full, by particles with fresh random streams, as it
  /// stands (a goal-reaching one cut where it settled): its belief and goal fraction are
  /// then not the best of several noisy estimates.
  void confirm(Candidate& candidate, const Motion& from);
  /// The candidate's particle motions from the end of `from`, with its random streams.
  ParticleRequest particleRequest(const Candidate& candidate, const Motion& from) const;
  /// The candidate the expansion keeps (null if none is valid): a goal candidate good enough
  /// to end the search, else a random one (randomCandidate), else the most robust.
  Candidate* chooseCandidate(CandidateDraw& draw, const Motion& from);
  /// Lazily: runs and judges the candidates in order until one is certain, and returns it;
  /// null if none is, or a run reaches the goal, or the random keep was drawn (`keepRandom`,
  /// drawn at the first valid candidate): then every one is needed.
  Candidate* firstCertain(CandidateDraw& draw, const Motion& from, std::optional<bool>& keepRandom);
  /// The goal candidate of highest belief whose plan is estimated to succeed often enough.
  Candidate* bestGoalCandidate(std::vector<Candidate>& valid, const Motion& from);
  /// The first candidate of highest belief (pruneCandidates: judged only as far as needed).
  Candidate* mostRobust(std::vector<Candidate>& valid, const Motion& from);
  /// Whether this expansion keeps a random valid candidate (randomCandidate).
  bool drawRandomKeep();
  static bool isCertain(const Candidate* candidate);
  /// Judges `c` (unless it was) against `best`, the best of the candidates before it, pruned
  /// with pruneCandidates, and makes it the best if it beats it.
  void judgeInTurn(Candidate& c, Candidate*& best, const Motion& from);
  /// Whether the kept `best` won against other candidates' estimates (confirmUnrivalled).
  static void markRivalled(Candidate& best, const std::vector<Candidate>& valid);
  bool reachesGoal(const Candidate& candidate) const;
  /// The estimated success of the plan that would end with the candidate (goalConfidence).
  double solutionConfidence(const Candidate& candidate) const;
  static void computeImportance(Grid::Cell* cell, void* planner);
  void recordSolution(const Motion* end, bool exact, double distance);
  /// The plan from the root to `end`, one segment per expansion: the pieces of one expansion
  /// are one control held for their summed duration, as its particles ran it (and as an
  /// execution with control noise must draw it: once). Each segment is its last motion and
  /// its steps.
  static std::vector<std::pair<const Motion*, unsigned>> planSegments(const Motion* end);
  /// A plan that passed verification, kept until the search has `plans` of them.
  struct VerifiedPlan {
    Motion* end = nullptr;
    unsigned runs = 0;       ///< its verification and estimate runs (0 without verification)
    unsigned successes = 0;  ///< of those, the ones that succeeded
    /// Verified in a tree's process, its estimate still to be measured from these streams on
    /// (measureInPlanner).
    std::optional<PlanVerifier::Streams> toMeasure;
  };
  /// The plan ending with `end` (a motion that reaches the goal) if it may end the search:
  /// with uncertainty and verifyRuns (with particles or without), only if enough of its sampled
  /// executions succeed (PlanVerifier); then as many fresh executions give its estimated
  /// success (in a tree's process, parallel_trees, they are left to measureInPlanner). A plan
  /// that fails stays in the tree (restartOnRejection: a new tree follows).
  /// At the deadline a verification not yet decided does not pass, and the fresh executions
  /// made so far give the estimate (the verification's own when there are none).
  std::optional<VerifiedPlan> verifyPlan(Motion* end);
  /// verifyRuns fresh executions of the plan ending with `end`: its estimated success (kept as
  /// it was when the deadline leaves none), counted in verificationRuns_.
  VerificationResult measureEstimate(Motion* end);
  /// After the plan ending with `end` failed verification (learnFromExecutions): each of its
  /// motions takes as belief the mean of a Beta posterior, its particles' belief counting as
  /// n_p runs and the executions that began its control (all its rejected plans' so far) as
  /// the rest; then refreshPathBeliefs.
  void learnFromExecutions(Motion* end, const VerificationResult& result);
  /// Recomputes the current tree's path beliefs from its motions' beliefs, the cells' belief
  /// sums, and the motions the goal bias may expand from.
  void refreshPathBeliefs();
  /// The plan ending with `end` as an execution runs it: one control per segment.
  static std::vector<physics::ControlStep> planControls(const Motion* end);
  /// Records the collected plan (verified_, not empty) that succeeded most often over all its
  /// verification and estimate runs (the first of equals) as the solution; with more than one to
  /// choose from, fresh runs measure its estimate again, since the choice favours plans whose
  /// runs went well.
  ompl::base::PlannerStatus returnBestCollected();
  std::uint64_t nextStreamSeed();
  /// Adds a root motion at the start state to an empty tree.
  void plantRoot();
  /// True once the trees hold maxMotions motions together: the search ends as at its time limit.
  bool outOfMotions() const;
  /// True once the time limit solve() was given has passed (setDeadline).
  bool pastDeadline() const;
  /// True once the verified plans collected may end the search: `plans` of them, and one
  /// whose estimate reaches the aspiration.
  bool collectedEnough() const;
  /// At the first verified plan below the aspiration: the search may grow `patience` times
  /// the motions it holds now before it returns the best plan kept.
  void startPatience();
  /// True once the search has grown `patience` times the motions it held at its first
  /// verified plan below the aspiration.
  bool patienceSpent() const;
  /// Counts the expansion that just ended towards restartAfter; true when the tree is due to
  /// start afresh, for that or because it holds treeMotions motions.
  bool stalled();
  /// Forgets the tree for the search (its cells, the motions near the goal) and plants a new
  /// root; the old motions stay, so the nearest of all can still be an approximate solution.
  void startAfresh();
  /// startAfresh() for the tree numbered `tree` (0 the first), whose pushes the goal steering
  /// may turn by an angle of the tree's own (push_angle_spread).
  void startTree(std::size_t tree);
  void resetCounters();

  /// How a tree's growth ended: with a verified plan, given up (stalled, full, or its plan
  /// rejected with restartOnRejection), or stopped (time, ptc, maxMotions, patience).
  enum class TreeEnd : std::uint64_t { Verified = 0, Abandoned = 1, Stopped = 2 };
  TreeEnd growTree(const ompl::base::PlannerTerminationCondition& ptc);
  /// The search's outcome once no tree goes on: the best verified plan, else the motion
  /// nearest the goal as an approximate solution.
  ompl::base::PlannerStatus finish();

  // parallel_trees (PKpieceTrees.cpp): tree k grows in a process of its own from the planner as
  // it was when the search began, with random streams of its own (reseedForTree), and the
  // search ends with the first tree, in index order, that ends it.
  ompl::base::PlannerStatus solveTreeByTree(const ompl::base::PlannerTerminationCondition& ptc);
  void reseedForTree(std::size_t tree);
  /// The counts a tree's process sends back, each added to the search's.
  std::array<std::uint64_t*, 12> searchCounts();
  /// In tree k's process: grows it, and packs how it ended, its counts and its plan (or the
  /// motion nearest the goal) for this process.
  std::vector<unsigned char> growTreeForSearch(std::size_t tree, TreeProcesses::LentCores& lent,
                                               const ompl::base::PlannerTerminationCondition& ptc);
  /// In a tree's process: spreads the particles and verifications over the cores the search
  /// has lent it since the last call (the same results on any number).
  void useLentCores();
  /// Whether this is a tree's process: a verified plan's estimate is then left to the
  /// planner's process (measureInPlanner).
  bool inTreeProcess() const { return lentCores_ != nullptr; }
  /// Takes a tree's packed result into this planner; how the tree ended.
  TreeEnd settleTree(const std::vector<unsigned char>& result);
  /// The estimate of the plan a tree's process verified, measured here on every core, with
  /// the streams the tree would have used: the same runs, the same estimate, in less time.
  void measureInPlanner(VerifiedPlan& plan);

  physics::PlanningContext& context_;
  PKpieceSettings settings_;
  MotionEvaluator evaluator_;
  ompl::RNG rng_;
  std::mt19937_64 fitRng_;    ///< EM seeding
  std::uint64_t streamBase_;  ///< particle streams derive from this and a counter
  std::uint64_t streamCounter_ = 0;
  Grid grid_;  ///< over the end-effector projection (2 or 3 dimensions)
  std::vector<std::unique_ptr<Motion>> motions_;
  std::vector<std::unique_ptr<CellData>> cells_;
  /// The goal bias's rank of the current tree's motion nearest the goal (restartAfter).
  double treeBestRank_ = std::numeric_limits<double>::infinity();
  /// The nearest the tree got by GoalSteering::learningRank, when the push angles learn
  /// (PushAngles::learns): what the trees after it learn from.
  double treeLearningRank_ = std::numeric_limits<double>::infinity();
  /// The motions nearest the goal among those a solution may grow from (see addMotion), nearest
  /// first.
  std::vector<Motion*> goalStarts_;
  unsigned iteration_ = 1;
  double beliefMeanSum_ = 0.0;  ///< sum over cells of their mean motion belief
  std::uint64_t candidateCount_ = 0;
  std::uint64_t goalCandidates_ = 0;     ///< candidates whose nominal run entered the goal
  double bestGoalConfidence_ = 0.0;      ///< the best solutionConfidence among them
  std::uint64_t steeredCandidates_ = 0;  ///< candidates aimed by GoalSteering
  std::uint64_t steeredValid_ = 0;       ///< of those, the ones valid from their first step
  std::uint64_t steeredKept_ = 0;        ///< of those, the ones chosen
  std::uint64_t keptCandidates_ = 0;     ///< expansions that kept a candidate
  std::uint64_t confirmations_ = 0;      ///< kept candidates judged again (confirm)
  FailureTally candidateFailures_;       ///< candidates whose nominal run broke a rule
  FailureTally steeredFailures_;         ///< of those, the steered ones
  std::vector<double> solutionBeliefs_;
  double solutionPathBelief_ = 1.0;
  std::optional<double> solutionConfidence_;  ///< the exact solution's estimated success
  ompl::base::State* scratch_ = nullptr;      ///< for projecting raw states
  std::shared_ptr<const RobotSpread::Part> robotPart_;
  GoalSteering steering_;
  PlanVerifier verifier_;
  std::uint64_t verifications_ = 0;           ///< plans executed in sampled worlds (verifyRuns)
  std::uint64_t verificationRejections_ = 0;  ///< of those, the ones that did not pass
  std::uint64_t verificationRuns_ = 0;        ///< sampled executions those and the estimates ran
  std::vector<VerifiedPlan> verified_;        ///< the plans that passed, in the order found
  std::optional<DeadlinePlanner::Clock::time_point> deadline_;  ///< the time limit's end
  std::optional<std::size_t> patienceEnd_;  ///< motions at which patienceSpent()
  bool steerNext_ = false;                ///< the motion being expanded was chosen by the goal bias
  Motion* closest_ = nullptr;             ///< the motion nearest the goal over every tree
  double progressRank_ = 0.0;             ///< the rank the current tree last came 1 cm nearer to
  unsigned expansionsSinceProgress_ = 0;  ///< expansions since then (restartAfter)
  std::size_t treeStart_ = 0;       ///< motions_'s index of the current tree's root (treeMotions)
  std::uint64_t restarts_ = 0;      ///< times the tree started afresh
  bool motionBudgetSpent_ = false;  ///< the last solve() ended at maxMotions
  unsigned treeProcesses_ = 1;      ///< trees grown at once (parallel_trees)
  /// In a tree's process (only there): where the cores the search lends it arrive.
  TreeProcesses::LentCores* lentCores_ = nullptr;
  std::uint64_t coresLent_ = 0;       ///< cores lent to trees that held up the search's end
  std::uint64_t treeSeedBase_ = 0;    ///< tree k's streams derive from this and k (parallel_trees)
  std::uint64_t discardedTrees_ = 0;  ///< trees grown past the one that ended the search
  std::uint64_t grownMotions_ = 0;    ///< motions the trees grew, in every process
};

}  // namespace kautham::planners

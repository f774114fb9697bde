#include "kautham/planners/pkpiece/PKpiece.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include <ompl/base/PlannerData.h>
#include <ompl/control/PathControl.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>
#include <ompl/datastructures/PDF.h>
#include <ompl/util/RandomNumbers.h>

#include "PKpieceMotion.h"
#include "kautham/physics/WorldStateSpace.h"
#include "kautham/planners/BeliefVertex.h"
#include "kautham/planners/pkpiece/ExecutionBelief.h"

namespace kautham::planners {

namespace {
// Cell scores as in KPIECE: an expansion that adds a motion keeps most of the cell's score,
// one that fails halves it, so cells that stop producing fade.
constexpr double kGoodScoreFactor = 0.9;
constexpr double kBadScoreFactor = 0.45;
constexpr std::size_t kNearestKept = 30;  // motions nearest the goal kept for the goal bias
// How much nearer the goal (in the goal bias's ranking, m) the tree's nearest motion must come
// for the search to count as getting on (restartAfter).
constexpr double kProgress = 0.01;
}  // namespace

struct PKpiece::CellData {
  std::vector<Motion*> motions;  ///< oldest first
  unsigned selections = 1;       ///< C: times the cell was chosen for expansion
  double score = 1.0;            ///< exploration progress
  unsigned iteration = 1;        ///< I: the iteration that created the cell
  double beliefSum = 0.0;        ///< sum of the beliefs of its motions
  double importance = 0.0;
  unsigned neighbors = 0;
  double meanBelief() const { return motions.empty() ? 0.0 : beliefSum / motions.size(); }
};

struct PKpiece::Candidate {
  std::vector<double> control;
  NominalRun run;
  std::vector<unsigned> pieceEnds;  ///< steps after which the motion is cut (see expand)
  /// Steps after which its particles' states are kept: the piece ends, and every step the
  /// nominal run spent in the goal.
  std::vector<unsigned> recordAfter;
  std::uint64_t streamSeed = 0;  ///< its particles' random streams
  double fromPathBelief = 1.0;   ///< the path belief of the motion it grows from
  bool judged = false;           ///< verdict holds its particles' (possibly pruned) say
  bool rivalled = false;  ///< kept over others' estimates, or a goal candidate (confirmUnrivalled)
  bool steered = false;   ///< aimed by GoalSteering (else random)
  ParticleVerdict verdict;
};

bool PKpiece::ByImportance::operator()(const CellData* a, const CellData* b) const {
  return a->importance > b->importance;
}

PKpiece::PKpiece(physics::PlanningContext& context, const PKpieceSettings& settings)
    : ompl::base::Planner(context.spaceInformation(), "p-KPIECE"),
      context_(context),
      settings_(settings),
      evaluator_(context, settings.displacement),
      fitRng_(rng_.uniformInt(0, std::numeric_limits<int>::max())),
      streamBase_(static_cast<std::uint64_t>(rng_.uniformInt(0, std::numeric_limits<int>::max()))
                  << 20),
      grid_(context.projection().getDimension()),
      robotPart_(std::make_shared<const RobotSpread::Part>(context.layout())),
      steering_(context, evaluator_, settings.clearingPush,
                pushSettingsOf(settings, ompl::RNG::getSeed()), settings.kinematicSteering,
                approachSettingsOf(settings)),
      // Verification streams: a function of the seed, apart from the particles' (and from
      // `kautham validate`'s, whose seeds are small numbers).
      verifier_(evaluator_, streamBase_ ^ 0x5645524946590000ULL),
      treeSeedBase_(streamBase_ ^ 0x5452454553000000ULL) {
  specs_.approximateSolutions = true;
  evaluator_.setNominalMargins(settings.tiltMargin, settings.targetMargin);
  scratch_ = si_->allocState();
  grid_.onCellUpdate(&PKpiece::computeImportance, this);
  addPlannerProgressProperty("cells INTEGER", [this] { return std::to_string(cells_.size()); });
  addPlannerProgressProperty("candidates INTEGER",
                             [this] { return std::to_string(candidateCount_); });
  // How near the search came to ending: candidates that entered the goal, and the best
  // estimated success among them (goal_confidence is what ends the search).
  addPlannerProgressProperty("goal_candidates INTEGER",
                             [this] { return std::to_string(goalCandidates_); });
  addPlannerProgressProperty("best_goal_confidence REAL", [this] {
    return goalCandidates_ == 0 ? std::string("nan") : std::to_string(bestGoalConfidence_);
  });
  // Plans executed in sampled worlds before one ended the search, and those that failed.
  addPlannerProgressProperty("verifications INTEGER",
                             [this] { return std::to_string(verifications_); });
  addPlannerProgressProperty("verification_rejections INTEGER",
                             [this] { return std::to_string(verificationRejections_); });
  // Plans that passed verification and were kept to choose from (plans > 1).
  addPlannerProgressProperty("verified_plans INTEGER",
                             [this] { return std::to_string(verified_.size()); });
  // Sampled executions run by the verifications and the estimate (verify_runs each at most).
  addPlannerProgressProperty("verification_runs INTEGER",
                             [this] { return std::to_string(verificationRuns_); });
  // Goal-biased expansions: candidates aimed by the goal steering, those valid from their first
  // step, and those kept (they compete with the random ones by belief).
  addPlannerProgressProperty("steered_candidates INTEGER",
                             [this] { return std::to_string(steeredCandidates_); });
  addPlannerProgressProperty("steered_valid INTEGER",
                             [this] { return std::to_string(steeredValid_); });
  addPlannerProgressProperty("steered_kept INTEGER",
                             [this] { return std::to_string(steeredKept_); });
  // Steered motions that inverse kinematics could not aim (kinematic_steering), or all of them
  // without it: the Jacobian aimed them.
  addPlannerProgressProperty("steered_by_jacobian INTEGER",
                             [this] { return std::to_string(steering_.jacobianAims()); });
  // Times the tree was started afresh: stalled (restart_after) or full (tree_motions).
  addPlannerProgressProperty("restarts INTEGER", [this] { return std::to_string(restarts_); });
  // Motions grown over every tree (with parallel_trees the planner data holds only the paths to
  // each tree's plan or motion nearest the goal).
  addPlannerProgressProperty("grown_motions INTEGER",
                             [this] { return std::to_string(grownMotions_); });
  // parallel_trees: trees grown at once with others and not taken in, as a tree before them
  // ended the search or the time ran out first (their work is not in the other counts).
  addPlannerProgressProperty("discarded_trees INTEGER",
                             [this] { return std::to_string(discardedTrees_); });
  // parallel_trees: cores lent to a tree still growing once a later one had ended the search,
  // which would otherwise have waited idle for it (its particles and verifications ran there).
  addPlannerProgressProperty("lent_cores INTEGER", [this] { return std::to_string(coresLent_); });
  // 1 when the search ended because its trees hold max_motions motions, not at the time limit.
  addPlannerProgressProperty("motion_budget_spent INTEGER",
                             [this] { return std::to_string(motionBudgetSpent_ ? 1 : 0); });
  // Expansions that kept a candidate, and those whose kept candidate was judged again
  // (confirm_belief, confirm_unrivalled).
  addPlannerProgressProperty("kept_candidates INTEGER",
                             [this] { return std::to_string(keptCandidates_); });
  addPlannerProgressProperty("confirmations INTEGER",
                             [this] { return std::to_string(confirmations_); });
  addPlannerProgressProperty("particles INTEGER",
                             [this] { return std::to_string(evaluator_.particleCount()); });
  // Particle judgements the sequential test ended early (certain_after).
  addPlannerProgressProperty("certain_early INTEGER",
                             [this] { return std::to_string(evaluator_.certainEarly()); });
  addPlannerProgressProperty("mean_solution_belief REAL", [this] {
    if (solutionBeliefs_.empty()) return std::string("nan");
    double sum = 0.0;
    for (double b : solutionBeliefs_) sum += b;
    return std::to_string(sum / solutionBeliefs_.size());
  });
  addPlannerProgressProperty("solution_path_belief REAL", [this] {
    return solutionBeliefs_.empty() ? std::string("nan") : std::to_string(solutionPathBelief_);
  });
  // The plan's estimated execution success: what goal_confidence compared, for the candidate
  // that ended the search (empty for an approximate solution).
  addPlannerProgressProperty("solution_confidence REAL", [this] {
    return solutionConfidence_ ? std::to_string(*solutionConfidence_) : std::string("nan");
  });
}

PKpiece::~PKpiece() {
  clear();
  si_->freeState(scratch_);
}

void PKpiece::clear() {
  Planner::clear();
  for (auto& motion : motions_) si_->freeState(motion->state);
  motions_.clear();
  grid_.clear();
  cells_.clear();
  treeBestRank_ = std::numeric_limits<double>::infinity();
  treeLearningRank_ = std::numeric_limits<double>::infinity();
  goalStarts_.clear();
  iteration_ = 1;
  beliefMeanSum_ = 0.0;
  resetCounters();
  solutionBeliefs_.clear();
  solutionConfidence_.reset();
  verified_.clear();
  patienceEnd_.reset();
  deadline_.reset();  // the next solve() is given its own
  verifier_.stopAt(std::nullopt);
  closest_ = nullptr;
  expansionsSinceProgress_ = 0;
  treeStart_ = 0;
  motionBudgetSpent_ = false;
  steering_.pushAngles().forget();  // a new search starts again from tree 0
}

void PKpiece::resetCounters() {
  candidateCount_ = 0;
  goalCandidates_ = 0;
  steeredCandidates_ = 0;
  steeredValid_ = 0;
  steeredKept_ = 0;
  keptCandidates_ = 0;
  confirmations_ = 0;
  candidateFailures_ = FailureTally{};
  steeredFailures_ = FailureTally{};
  evaluator_.resetCounts();
  steering_.resetCount();
  bestGoalConfidence_ = 0.0;
  verifications_ = 0;
  verificationRejections_ = 0;
  verificationRuns_ = 0;
  restarts_ = 0;
  discardedTrees_ = 0;
  grownMotions_ = 0;
  coresLent_ = 0;
}

void PKpiece::setThreads(unsigned threads) {
  if (settings_.parallelTrees)
    treeProcesses_ = std::max(1u, threads);
  else
    evaluator_.useWorkers(threads);
}

std::uint64_t PKpiece::nextStreamSeed() {
  // Each candidate gets its own block of particle streams (one per particle).
  return streamBase_ + (streamCounter_++) * 1024;
}

void PKpiece::computeImportance(Grid::Cell* cell, void* planner) {
  const auto& self = *static_cast<const PKpiece*>(planner);
  CellData& d = *cell->data;
  const double cellCount = static_cast<double>(self.cells_.size());
  const double f = self.settings_.beliefWeight > 0.0 ? self.settings_.beliefWeight : cellCount;
  const double normalizedBelief =
      self.beliefMeanSum_ > 0.0 ? d.meanBelief() / self.beliefMeanSum_ : 0.0;
  // The paper's log(I) is 0 for the first cell; 1 + log(I) keeps it positive.
  const double age = 1.0 + std::log(static_cast<double>(d.iteration));
  d.importance = (1.0 + f * normalizedBelief) * age * d.score /
                 (d.selections * (1.0 + cell->neighbors) * d.motions.size());
}

void PKpiece::addMotion(Motion* motion) {
  Grid::Coord coord(context_.projection().getDimension());
  context_.projection().computeCoordinates(motion->state, coord);
  Grid::Cell* cell = grid_.getCell(coord);
  if (!cell) {
    cell = grid_.createCell(coord);
    cells_.push_back(std::make_unique<CellData>());
    cell->data = cells_.back().get();
    cell->data->iteration = iteration_;
    grid_.add(cell);
  }
  CellData& data = *cell->data;
  beliefMeanSum_ -= data.meanBelief();
  data.motions.push_back(motion);
  data.beliefSum += selectionBelief(*motion);
  beliefMeanSum_ += data.meanBelief();
  motion->cell = &data;

  treeBestRank_ = std::min(treeBestRank_, motion->goalDistance);
  if (steering_.pushAngles().learns())
    treeLearningRank_ = std::min(
        treeLearningRank_, steering_.learningRank(physics::WorldStateSpace::values(motion->state)));
  if (!closest_ || motion->goalDistance < closest_->goalDistance) closest_ = motion;
  if (mayEndAPlan(*motion)) keepIfNear(goalStarts_, motion);
}

bool PKpiece::mayEndAPlan(const Motion& motion) const {
  // Only a motion whose path is believed at least as much as a solution must be can end
  // one: the goal bias expands from those.
  return !settings_.pathBelief || motion.pathBelief >= settings_.goalConfidence;
}

void PKpiece::keepIfNear(std::vector<Motion*>& nearest, Motion* motion) {
  nearest.push_back(motion);
  std::sort(nearest.begin(), nearest.end(),
            [](const Motion* a, const Motion* b) { return a->goalDistance < b->goalDistance; });
  if (nearest.size() > kNearestKept) nearest.pop_back();
}

PKpiece::Motion* PKpiece::nearGoalMotion() {
  ompl::PDF<Motion*> pdf;
  for (Motion* m : goalStarts_) pdf.add(m, 1.0 / (m->goalDistance + 0.01));
  return pdf.sample(rng_.uniform01());
}

double PKpiece::selectionBelief(const Motion& motion) const {
  return settings_.pathBelief ? motion.pathBelief : motion.belief;
}

PKpiece::Motion* PKpiece::selectInCell(const CellData& cell) {
  const auto& motions = cell.motions;
  if (rng_.uniform01() < settings_.kpieceSelection) {
    // As KPIECE does: a half-normal over the motions, newest first.
    const int last = static_cast<int>(motions.size()) - 1;
    return motions[static_cast<std::size_t>(last - rng_.halfNormalInt(0, last))];
  }
  double best = -1.0;
  std::vector<Motion*> ties;
  for (Motion* m : motions) {
    const double belief = selectionBelief(*m);
    if (belief > best + 1e-12) {
      best = belief;
      ties.assign(1, m);
    } else if (std::abs(belief - best) <= 1e-12) {
      ties.push_back(m);
    }
  }
  return ties[static_cast<std::size_t>(rng_.uniformInt(0, static_cast<int>(ties.size()) - 1))];
}

PKpiece::Motion* PKpiece::selectMotion() {
  steerNext_ = !goalStarts_.empty() && rng_.uniform01() < settings_.goalBias;
  if (steerNext_) return nearGoalMotion();
  const bool exterior = grid_.countExternal() > 0 &&
                        (grid_.countInternal() == 0 || rng_.uniform01() < settings_.borderFraction);
  Grid::Cell* cell = exterior ? grid_.topExternal() : grid_.topInternal();
  cell->data->selections += 1;
  return selectInCell(*cell->data);
}

PKpiece::CandidateDraw PKpiece::drawCandidates(const Motion& from) {
  const auto& si = context_.spaceInformation();
  const unsigned minSteps = si->getMinControlDuration();
  const unsigned maxSteps = si->getMaxControlDuration();
  const std::size_t dimension = si->getControlSpace()->getDimension();
  // Everything random is drawn first, whichever candidates then run: a candidate is the same
  // however many run before it.
  CandidateDraw draw;
  draw.motions.resize(settings_.candidates);
  for (NominalMotion& motion : draw.motions) {
    motion.control.resize(dimension);
    for (double& u : motion.control) u = rng_.uniformReal(-1.0, 1.0);
    motion.steps = static_cast<unsigned>(
        rng_.uniformInt(static_cast<int>(minSteps), static_cast<int>(maxSteps)));
  }
  // A goal-biased expansion tries one candidate aimed at the goal (GoalSteering), first.
  if (steerNext_ && settings_.goalSteering)
    if (std::optional<NominalMotion> aimed =
            steering_.towardsGoal(physics::WorldStateSpace::values(from.state))) {
      draw.motions[0] = *aimed;
      draw.steered = true;
      ++steeredCandidates_;
    }
  // Pointers into valid stay put while it grows (chooseCandidate holds them).
  draw.valid.reserve(draw.motions.size());
  return draw;
}

void PKpiece::runCandidates(CandidateDraw& draw, const Motion& from, std::size_t upTo) {
  if (upTo <= draw.ran) return;
  const double* start = physics::WorldStateSpace::values(from.state);
  const std::vector<NominalMotion> motions(draw.motions.begin() + draw.ran,
                                           draw.motions.begin() + upTo);
  // Every candidate runs on through the goal, so that settleInGoal can end it deep inside: one
  // that stopped where it entered would end on the region's border (with particles or without).
  // Several go to the worker processes together.
  std::vector<NominalRun> runs = evaluator_.runNominals(start, motions, true);
  candidateCount_ += motions.size();
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const bool steered = draw.steered && draw.ran + i == 0;
    tallyBrokenRule(runs[i], steered);
    if (runs[i].steps == 0) continue;  // invalid from its first step
    draw.valid.push_back(admit(motions[i].control, std::move(runs[i]), steered, from));
  }
  draw.ran = upTo;
}

PKpiece::Candidate PKpiece::admit(const std::vector<double>& control, NominalRun&& run,
                                  bool steered, const Motion& from) {
  Candidate candidate;
  candidate.control = control;
  candidate.run = std::move(run);
  // A run through the goal that never gets deep enough to end a plan is an ordinary motion:
  // judged in full as a goal candidate, its particles would be spent for nothing.
  if (candidate.run.reachedGoal && !getsDeepEnough(candidate.run)) {
    candidate.run.reachedGoal = false;
    candidate.run.goalFrom = 0;
  }
  candidate.streamSeed = nextStreamSeed();
  candidate.fromPathBelief = from.pathBelief;
  candidate.steered = steered;
  steeredValid_ += steered ? 1 : 0;
  candidate.pieceEnds = pieceEnds(candidate.run);
  candidate.recordAfter = candidate.pieceEnds;
  for (unsigned s = candidate.run.goalFrom; s > 0 && s <= candidate.run.steps; ++s)
    candidate.recordAfter.push_back(s);
  std::sort(candidate.recordAfter.begin(), candidate.recordAfter.end());
  candidate.recordAfter.erase(
      std::unique(candidate.recordAfter.begin(), candidate.recordAfter.end()),
      candidate.recordAfter.end());
  return candidate;
}

void PKpiece::judge(Candidate& candidate, const Motion& from, double toBeat) {
  const double* start = physics::WorldStateSpace::values(from.state);
  candidate.judged = true;
  if (!withParticles()) {
    // Without uncertainty the nominal run is the only particle (the paper's pKP column).
    if (candidate.run.reachedGoal) settleInGoal(candidate);
    candidate.verdict = evaluator_.judgeNominal(start, candidate.run.end.data());
    return;
  }
  candidate.verdict = evaluator_.runParticles(particleRequest(candidate, from), toBeat);
  if (candidate.run.reachedGoal && !candidate.verdict.pruned) settleInGoal(candidate);
}

void PKpiece::confirm(Candidate& candidate, const Motion& from) {
  // chooseCandidate judged it already: a goal-reaching one is cut where it settled.
  candidate.streamSeed = nextStreamSeed();
  candidate.recordAfter = candidate.pieceEnds;
  candidate.verdict = evaluator_.runParticles(particleRequest(candidate, from), -1.0);
}

ParticleRequest PKpiece::particleRequest(const Candidate& candidate, const Motion& from) const {
  ParticleRequest request;
  request.start = physics::WorldStateSpace::values(from.state);
  request.control = candidate.control.data();
  request.steps = candidate.run.steps;
  request.poses = from.poses.get();
  request.robots = from.robotSpread.get();
  request.recordAfter = candidate.recordAfter;
  request.particles = settings_.particles;
  request.certainAfter = candidate.run.reachedGoal ? 0 : settings_.certainAfter;
  request.streamSeed = candidate.streamSeed;
  return request;
}

bool PKpiece::withParticles() const { return settings_.uncertainty && settings_.particles > 0; }

std::size_t PKpiece::recordIndex(const Candidate& candidate, unsigned step) {
  const auto& steps = candidate.recordAfter;
  const auto found = std::lower_bound(steps.begin(), steps.end(), step);
  if (found == steps.end() || *found != step)
    throw std::logic_error("p-KPIECE: no particle states recorded after step " +
                           std::to_string(step));
  return static_cast<std::size_t>(found - steps.begin());
}

void PKpiece::settleInGoal(Candidate& candidate) const {
  // The nominal run went on while it stayed in the goal; where it entered is the region's
  // border, which a particle (or an execution with control noise) misses as often as it hits.
  // It ends at the step where most particles are inside too, and of equals (always, without
  // particles) where the nominal run is nearest the goal point.
  // Only a step deep enough in the region may end a plan (goal_margin); admit made
  // a run that gets no deeper an ordinary motion, so some step here is deep enough.
  const bool particles = withParticles();
  NominalRun& run = candidate.run;
  const double deepEnough = deepEnoughDistance();
  unsigned bestStep = run.goalFrom;
  unsigned bestCount = 0;
  double bestDistance = std::numeric_limits<double>::infinity();
  for (unsigned step = run.goalFrom; step <= run.steps; ++step) {
    const unsigned count =
        particles ? candidate.verdict.inGoalAt(recordIndex(candidate, step)) : 0u;
    const double distance = context_.goal().distance(run.states[step - 1].data());
    if (distance > deepEnough) continue;
    if (count > bestCount || (count == bestCount && distance < bestDistance)) {
      bestCount = count;
      bestDistance = distance;
      bestStep = step;
    }
  }
  if (particles) candidate.verdict = candidate.verdict.cutAt(recordIndex(candidate, bestStep));
  run.states.resize(bestStep);
  run.end = run.states.back();
  run.steps = bestStep;
  candidate.pieceEnds = pieceEnds(run);
  if (!particles) candidate.recordAfter = candidate.pieceEnds;
}

bool PKpiece::getsDeepEnough(const NominalRun& run) const {
  const double deepEnough = deepEnoughDistance();
  for (unsigned step = run.goalFrom; step > 0 && step <= run.steps; ++step)
    if (context_.goal().distance(run.states[step - 1].data()) <= deepEnough) return true;
  return false;
}

double PKpiece::deepEnoughDistance() const {
  // The tolerance in what WorkspaceGoal::distance measures: metres, or normalized joint units
  // for a configuration goal.
  const physics::GoalSpec& spec = context_.goal().spec();
  return settings_.goalMargin * (spec.joints.empty() ? spec.tolerance : spec.jointTolerance);
}

double PKpiece::solutionConfidence(const Candidate& c) const {
  // How likely the plan ending with this candidate is to succeed: the path to it is valid,
  // and then its particles end valid in the goal.
  return (settings_.pathBelief ? c.fromPathBelief : 1.0) * c.verdict.goal;
}

bool PKpiece::reachesGoal(const Candidate& c) const {
  return c.run.reachedGoal && c.judged && !c.verdict.pruned &&
         solutionConfidence(c) >= settings_.goalConfidence;
}

PKpiece::Candidate* PKpiece::chooseCandidate(CandidateDraw& draw, const Motion& from) {
  std::optional<bool> keepRandom;
  if (settings_.lazyCandidates && settings_.pruneCandidates)
    if (Candidate* certain = firstCertain(draw, from, keepRandom)) return certain;
  // Every candidate run (lazily, the ones judged so far keep their verdicts).
  runCandidates(draw, from, draw.motions.size());
  std::vector<Candidate>& valid = draw.valid;
  if (valid.empty()) return nullptr;
  if (Candidate* goal = bestGoalCandidate(valid, from)) return goal;
  if (!keepRandom) keepRandom = drawRandomKeep();
  if (*keepRandom) {
    Candidate& c =
        valid[static_cast<std::size_t>(rng_.uniformInt(0, static_cast<int>(valid.size()) - 1))];
    if (!c.judged) judge(c, from, -1.0);
    return &c;
  }
  return mostRobust(valid, from);
}

PKpiece::Candidate* PKpiece::firstCertain(CandidateDraw& draw, const Motion& from,
                                          std::optional<bool>& keepRandom) {
  // As mostRobust judges them, in order, but each run only when the ones before leave the
  // choice open. A run that reaches the goal stops it unjudged: goal candidates come first.
  Candidate* best = nullptr;
  while (draw.ran < draw.motions.size()) {
    const std::size_t before = draw.valid.size();
    runCandidates(draw, from, draw.ran + 1);
    if (draw.valid.size() == before) continue;  // invalid from its first step
    Candidate& c = draw.valid.back();
    if (c.run.reachedGoal) return nullptr;
    // The random keep needs every candidate run: drawn once there is one to keep, as when all
    // run first (never in an expansion without a valid candidate, nor before the goal step).
    if (!keepRandom) {
      keepRandom = drawRandomKeep();
      if (*keepRandom) return nullptr;
    }
    judgeInTurn(c, best, from);
    if (isCertain(best)) {
      markRivalled(*best, draw.valid);
      return best;
    }
  }
  return nullptr;  // none certain: mostRobust chooses among them, all judged
}

bool PKpiece::drawRandomKeep() { return rng_.uniform01() < settings_.randomCandidate; }

bool PKpiece::isCertain(const Candidate* c) { return c && c->verdict.belief() >= 1.0; }

void PKpiece::judgeInTurn(Candidate& c, Candidate*& best, const Motion& from) {
  const bool prune = settings_.pruneCandidates;
  if (!c.judged) judge(c, from, prune && best ? best->verdict.belief() : -1.0);
  if (!c.verdict.pruned && (!best || c.verdict.belief() > best->verdict.belief())) best = &c;
}

void PKpiece::markRivalled(Candidate& best, const std::vector<Candidate>& valid) {
  // The first candidate, certain or alone, is kept whatever the others' estimates (pruned, they
  // are never made): it won against none of them.
  best.rivalled = &best != &valid.front() || (valid.size() > 1 && best.verdict.belief() < 1.0);
}

PKpiece::Candidate* PKpiece::bestGoalCandidate(std::vector<Candidate>& valid, const Motion& from) {
  // A candidate that reaches the goal ends the search: the most robust of those is kept.
  Candidate* best = nullptr;
  for (Candidate& c : valid) {
    if (!c.run.reachedGoal) continue;
    judge(c, from, -1.0);
    ++goalCandidates_;
    bestGoalConfidence_ = std::max(bestGoalConfidence_, solutionConfidence(c));
    if (reachesGoal(c) && (!best || c.verdict.belief() > best->verdict.belief())) best = &c;
  }
  // A goal candidate passed the goal bar on its own estimate: it is always judged again.
  if (best) best->rivalled = true;
  return best;
}

PKpiece::Candidate* PKpiece::mostRobust(std::vector<Candidate>& valid, const Motion& from) {
  // The first candidate of highest belief, as if all were judged in full: a candidate stops
  // as soon as it cannot beat the best so far, and none is judged once one is certain.
  Candidate* best = nullptr;
  for (Candidate& c : valid) {
    if (settings_.pruneCandidates && isCertain(best)) break;
    judgeInTurn(c, best, from);
  }
  if (best) markRivalled(*best, valid);
  return best;
}

PKpiece::Motion* PKpiece::expand(Motion* from) {
  CandidateDraw draw = drawCandidates(*from);
  Candidate* chosen = chooseCandidate(draw, *from);
  if (!chosen) return nullptr;
  steeredKept_ += chosen->steered ? 1 : 0;
  ++keptCandidates_;
  if (settings_.confirmBelief && withParticles() &&
      (chosen->rivalled || settings_.confirmUnrivalled)) {
    confirm(*chosen, *from);
    ++confirmations_;
  }
  const double* start = physics::WorldStateSpace::values(from->state);
  const auto endPoses =
      from->poses->afterMotion(evaluator_.objectBodies(), start, chosen->run.end.data(),
                               chosen->verdict.starts, chosen->verdict.ends, fitRng_);
  // Pieces before the end carry the parent's pose distribution while no object has moved yet,
  // and once one has, the one fitted to where the particles had the objects at the piece's
  // end (the end's would put a can the gripper is still pushing where the push leaves it).
  const std::vector<std::vector<double>>& states = chosen->run.states;
  Motion* parent = from;
  unsigned pieceStart = 0;
  for (std::size_t k = 0; k < chosen->pieceEnds.size(); ++k) {
    const unsigned end = chosen->pieceEnds[k];
    const bool last = end == states.size();
    std::shared_ptr<const ObjectPoseBelief> poses = endPoses;
    if (!last)
      poses = objectsMoved(start, states[end - 1].data()) ? posesAfter(*chosen, end, *from)
                                                          : from->poses;
    parent = addPiece(parent, *chosen, states[end - 1], end - pieceStart, from->pathBelief,
                      std::move(poses), robotSpreadAt(*chosen, end, *from));
    pieceStart = end;
  }
  return parent;
}

std::shared_ptr<const ObjectPoseBelief> PKpiece::posesAfter(const Candidate& chosen, unsigned step,
                                                            const Motion& from) {
  // The particles that got this far: where each started, and its state after `step`.
  std::vector<std::vector<double>> starts, states;
  if (withParticles()) {
    const std::size_t record = recordIndex(chosen, step);
    for (std::size_t p : particlesAt(chosen, step)) {
      starts.push_back(chosen.verdict.starts[p]);
      states.push_back(chosen.verdict.recorded[p][record]);
    }
  }
  return from.poses->afterMotion(evaluator_.objectBodies(),
                                 physics::WorldStateSpace::values(from.state),
                                 chosen.run.states[step - 1].data(), starts, states, fitRng_);
}

std::vector<unsigned> PKpiece::pieceEnds(const NominalRun& run) const {
  // As KPIECE does, a kept motion is cut where its end effector changes cell: each piece is
  // a motion of the tree, so one expansion can cover several cells.
  std::vector<unsigned> ends;
  for (std::size_t i = 0; i < run.states.size(); ++i)
    if (i + 1 == run.states.size() || cellOf(run.states[i]) != cellOf(run.states[i + 1]))
      ends.push_back(static_cast<unsigned>(i + 1));
  return ends;
}

std::shared_ptr<const RobotSpread> PKpiece::robotSpreadAt(const Candidate& chosen, unsigned step,
                                                          const Motion& from) const {
  if (!settings_.robotSpread || !withParticles()) return nullptr;
  const std::vector<const std::vector<double>*> states = particleStatesAt(chosen, step);
  // No particle got this far (the belief says so): the parent's spread is the best guess;
  // the nominal robot alone would make what grows from here look certain.
  if (states.empty()) return from.robotSpread;
  std::vector<std::size_t> carried;
  if (settings_.objectSpread) {
    if (from.robotSpread) carried = from.robotSpread->objects();
    const double* start = physics::WorldStateSpace::values(from.state);
    for (std::size_t b : evaluator_.objectBodies())
      if (disturbed(b, start, chosen.run.states[step - 1].data(), states)) carried.push_back(b);
  }
  return RobotSpread::fromStates(robotPart_, states, std::move(carried));
}

std::vector<std::size_t> PKpiece::particlesAt(const Candidate& chosen, unsigned step) {
  const std::size_t record = recordIndex(chosen, step);
  std::vector<std::size_t> particles;
  for (std::size_t p = 0; p < chosen.verdict.recorded.size(); ++p)
    if (chosen.verdict.recorded[p].size() > record) particles.push_back(p);
  return particles;
}

std::vector<const std::vector<double>*> PKpiece::particleStatesAt(const Candidate& chosen,
                                                                  unsigned step) {
  const std::size_t record = recordIndex(chosen, step);
  std::vector<const std::vector<double>*> states;
  for (std::size_t p : particlesAt(chosen, step))
    states.push_back(&chosen.verdict.recorded[p][record]);
  return states;
}

bool PKpiece::disturbed(std::size_t body, const double* start, const double* nominal,
                        const std::vector<const std::vector<double>*>& particles) {
  constexpr double kMoved = 0.001;  // m the nominal run moved it
  constexpr double kMoving = 0.01;  // m/s a particle has it still sliding
  constexpr double kTurning = 0.1;  // rad/s a particle has it still turning or tipping
  if ((physics::WorldLayout::position(nominal, body) - physics::WorldLayout::position(start, body))
          .norm() > kMoved)
    return true;
  const std::size_t at = body * physics::WorldLayout::kBodyStateSize;
  for (const std::vector<double>* state : particles) {
    const double* v = state->data() + at + physics::WorldLayout::kLinearVelocity;
    const double* w = state->data() + at + physics::WorldLayout::kAngularVelocity;
    if (std::hypot(v[0], v[1], v[2]) > kMoving || std::hypot(w[0], w[1], w[2]) > kTurning)
      return true;
  }
  return false;
}

PKpiece::Grid::Coord PKpiece::cellOf(const std::vector<double>& state) const {
  std::copy(state.begin(), state.end(), physics::WorldStateSpace::values(scratch_));
  Grid::Coord coord(context_.projection().getDimension());
  context_.projection().computeCoordinates(scratch_, coord);
  return coord;
}

bool PKpiece::objectsMoved(const double* start, const double* state) const {
  constexpr double kMoved = 0.001;  // m
  for (std::size_t b : evaluator_.objectBodies())
    if ((physics::WorldLayout::position(state, b) - physics::WorldLayout::position(start, b))
            .norm() > kMoved)
      return true;
  return false;
}

PKpiece::Motion* PKpiece::addPiece(Motion* parent, const Candidate& chosen,
                                   const std::vector<double>& end, unsigned steps,
                                   double fromPathBelief,
                                   std::shared_ptr<const ObjectPoseBelief> poses,
                                   std::shared_ptr<const RobotSpread> robotSpread) {
  auto motion = std::make_unique<Motion>();
  motion->state = si_->allocState();
  double* values = physics::WorldStateSpace::values(motion->state);
  std::copy(end.begin(), end.end(), values);
  motion->control = chosen.control;
  motion->steps = steps;
  motion->parent = parent;
  motion->belief = chosen.verdict.belief();
  motion->particleBelief = motion->belief;
  motion->particleRuns = chosen.verdict.particles;
  // Every piece of one candidate shares its belief: multiply it in once.
  motion->pathBelief = fromPathBelief * motion->belief;
  motion->goalDistance = steering_.rankDistance(values);
  motion->poses = std::move(poses);
  motion->robotSpread = std::move(robotSpread);
  motion->expansion = iteration_;
  motion->reachesGoal = reachesGoal(chosen) && &end == &chosen.run.states.back();
  if (motion->reachesGoal) motion->successEstimate = solutionConfidence(chosen);
  Motion* raw = motion.get();
  motions_.push_back(std::move(motion));
  ++grownMotions_;
  addMotion(raw);
  return raw;
}

std::vector<std::pair<const PKpiece::Motion*, unsigned>> PKpiece::planSegments(const Motion* end) {
  std::vector<const Motion*> chain;
  for (const Motion* m = end; m->parent; m = m->parent) chain.push_back(m);
  std::reverse(chain.begin(), chain.end());
  std::vector<std::pair<const Motion*, unsigned>> segments;
  for (std::size_t i = 0; i < chain.size(); ++i) {
    unsigned steps = chain[i]->steps;
    while (i + 1 < chain.size() && chain[i + 1]->expansion == chain[i]->expansion)
      steps += chain[++i]->steps;
    segments.emplace_back(chain[i], steps);
  }
  return segments;
}

std::vector<physics::ControlStep> PKpiece::planControls(const Motion* end) {
  std::vector<physics::ControlStep> controls;
  for (const auto& [motion, steps] : planSegments(end))
    controls.push_back({motion->control, steps});
  return controls;
}

void PKpiece::setDeadline(Clock::time_point deadline) {
  deadline_ = deadline;
  verifier_.stopAt(deadline);
}

bool PKpiece::pastDeadline() const { return deadline_ && Clock::now() >= *deadline_; }

std::optional<PKpiece::VerifiedPlan> PKpiece::verifyPlan(Motion* end) {
  if (!settings_.uncertainty || settings_.verifyRuns == 0)
    return VerifiedPlan{end, 0, 0, std::nullopt};
  const std::vector<physics::ControlStep> controls = planControls(end);
  ++verifications_;
  const VerificationResult result =
      verifier_.verify(controls, settings_.verifyRuns, settings_.goalConfidence);
  verificationRuns_ += result.runs;
  if (result.passed) {
    // The first plan to pass is, among all those tried, one whose runs went well: fresh
    // runs, whatever they find, give its estimated success without that bias.
    end->successEstimate = result.rate();  // until they do
    // A tree's process has one core; the planner's has them all once the tree is taken in.
    if (inTreeProcess())
      return VerifiedPlan{end, result.runs, result.successes, verifier_.streams()};
    const VerificationResult fresh = measureEstimate(end);
    return VerifiedPlan{end, result.runs + fresh.runs, result.successes + fresh.successes,
                        std::nullopt};
  }
  if (result.cutShort) return std::nullopt;  // undecided: the search ends, the plan stays
  ++verificationRejections_;
  end->reachesGoal = false;
  if (settings_.learnFromExecutions) learnFromExecutions(end, result);
  return std::nullopt;
}

VerificationResult PKpiece::measureEstimate(Motion* end) {
  const VerificationResult fresh = verifier_.measure(planControls(end), settings_.verifyRuns);
  verificationRuns_ += fresh.runs;
  // Cut short by the deadline before its first run: the estimate it had stays.
  if (fresh.runs > 0) end->successEstimate = fresh.rate();
  return fresh;
}

void PKpiece::learnFromExecutions(Motion* end, const VerificationResult& result) {
  // The plan's motions, root first; each expansion's pieces make one control.
  std::vector<Motion*> chain;
  for (Motion* m = end; m->parent; m = m->parent) chain.push_back(m);
  std::reverse(chain.begin(), chain.end());
  std::size_t control = 0;
  for (std::size_t i = 0; i < chain.size(); ++i) {
    if (i > 0 && chain[i]->expansion != chain[i - 1]->expansion) ++control;
    if (control >= result.entered.size()) break;  // cannot happen: one control per expansion
    Motion& m = *chain[i];
    m.executionsThrough += result.entered[control];
    m.executionsPassed += result.gotThrough[control];
    m.belief = beliefAfterExecutions(m.particleBelief, m.particleRuns, m.executionsThrough,
                                     m.executionsPassed);
  }
  refreshPathBeliefs();
}

void PKpiece::refreshPathBeliefs() {
  // Parents come before their children in motions_: one pass down the current tree.
  for (std::size_t i = treeStart_ + 1; i < motions_.size(); ++i) {
    Motion& m = *motions_[i];
    // The pieces of one candidate share its belief, multiplied in once (addPiece).
    m.pathBelief =
        m.parent->expansion == m.expansion ? m.parent->pathBelief : m.parent->pathBelief * m.belief;
  }
  beliefMeanSum_ = 0.0;
  for (const auto& cell : cells_) {
    cell->beliefSum = 0.0;
    for (const Motion* m : cell->motions) cell->beliefSum += selectionBelief(*m);
    beliefMeanSum_ += cell->meanBelief();
  }
  goalStarts_.clear();
  for (std::size_t i = treeStart_; i < motions_.size(); ++i)
    if (mayEndAPlan(*motions_[i])) keepIfNear(goalStarts_, motions_[i].get());
  grid_.updateAll();
}

ompl::base::PlannerStatus PKpiece::returnBestCollected() {
  const VerifiedPlan* best = &verified_.front();
  for (const VerifiedPlan& plan : verified_)
    // Cross-multiplied rates: exact, so equals stay equal and the first of them wins.
    if (static_cast<std::uint64_t>(plan.successes) * best->runs >
        static_cast<std::uint64_t>(best->successes) * plan.runs)
      best = &plan;
  if (verified_.size() > 1) measureEstimate(best->end);
  recordSolution(best->end, true, best->end->goalDistance);
  return ompl::base::PlannerStatus::EXACT_SOLUTION;
}

void PKpiece::recordSolution(const Motion* end, bool exact, double distance) {
  auto path = std::make_shared<ompl::control::PathControl>(si_);
  auto* csi = static_cast<ompl::control::SpaceInformation*>(si_.get());
  const double stepSize = csi->getPropagationStepSize();
  solutionBeliefs_.clear();
  solutionPathBelief_ = end->pathBelief;
  solutionConfidence_.reset();
  if (exact) solutionConfidence_ = end->successEstimate;
  const Motion* root = end;
  while (root->parent) root = root->parent;
  path->append(root->state);
  for (const auto& [motion, steps] : planSegments(end)) {
    ompl::control::Control* control = csi->allocControl();
    std::copy(motion->control.begin(), motion->control.end(),
              control->as<ompl::control::RealVectorControlSpace::ControlType>()->values);
    path->append(motion->state, control, steps * stepSize);
    csi->freeControl(control);
    solutionBeliefs_.push_back(motion->belief);
  }
  pdef_->addSolutionPath(path, !exact, distance, getName());
}

ompl::base::PlannerStatus PKpiece::solve(const ompl::base::PlannerTerminationCondition& ptc) {
  checkValidity();
  motionBudgetSpent_ = false;
  if (settings_.parallelTrees) return solveTreeByTree(ptc);
  if (motions_.empty()) plantRoot();
  for (;;) {
    const TreeEnd end = growTree(ptc);
    if (end == TreeEnd::Verified) {
      if (collectedEnough()) return returnBestCollected();
      startPatience();
      if (patienceSpent()) return returnBestCollected();
    }
    if (end == TreeEnd::Stopped) break;
    startAfresh();
  }
  return finish();
}

PKpiece::TreeEnd PKpiece::growTree(const ompl::base::PlannerTerminationCondition& ptc) {
  while (!ptc && !outOfMotions() && !pastDeadline() && !patienceSpent()) {
    useLentCores();
    Motion* from = selectMotion();
    CellData* cell = from->cell;
    Motion* added = expand(from);
    cell->score *= added ? kGoodScoreFactor : kBadScoreFactor;
    ++iteration_;
    grid_.updateAll();  // beliefs are normalised over all cells: every importance changes
    if (added && added->reachesGoal) {
      if (const std::optional<VerifiedPlan> plan = verifyPlan(added)) {
        verified_.push_back(*plan);
        return TreeEnd::Verified;
      }
      if (pastDeadline()) return TreeEnd::Stopped;
      if (settings_.restartOnRejection) return TreeEnd::Abandoned;
    }
    if (stalled()) return TreeEnd::Abandoned;
  }
  return TreeEnd::Stopped;
}

ompl::base::PlannerStatus PKpiece::finish() {
  motionBudgetSpent_ = outOfMotions();
  if (!verified_.empty()) return returnBestCollected();
  if (!closest_ || closest_->parent == nullptr) return ompl::base::PlannerStatus::TIMEOUT;
  recordSolution(closest_, false, closest_->goalDistance);
  return ompl::base::PlannerStatus::APPROXIMATE_SOLUTION;
}

void PKpiece::plantRoot() {
  auto root = std::make_unique<Motion>();
  root->state = si_->allocState();
  si_->copyState(root->state, pdef_->getStartState(0));
  const double* start = physics::WorldStateSpace::values(root->state);
  root->goalDistance = steering_.rankDistance(start);
  root->poses = settings_.uncertainty
                    ? ObjectPoseBelief::initial(context_.layout(), evaluator_.sampler(), start)
                    : std::make_shared<const ObjectPoseBelief>();
  Motion* raw = root.get();
  treeStart_ = motions_.size();
  motions_.push_back(std::move(root));
  ++grownMotions_;
  addMotion(raw);
  grid_.updateAll();
  progressRank_ = raw->goalDistance;
  expansionsSinceProgress_ = 0;
}

bool PKpiece::outOfMotions() const {
  return settings_.maxMotions > 0 && motions_.size() >= settings_.maxMotions;
}

bool PKpiece::collectedEnough() const {
  if (verified_.size() < settings_.plans) return false;
  return std::any_of(verified_.begin(), verified_.end(), [this](const VerifiedPlan& plan) {
    return plan.end->successEstimate >= settings_.aspiration;
  });
}

void PKpiece::startPatience() {
  if (settings_.aspiration <= 0.0 || patienceEnd_) return;
  patienceEnd_ = static_cast<std::size_t>(
      std::ceil(static_cast<double>(motions_.size()) * (1.0 + settings_.patience)));
}

bool PKpiece::patienceSpent() const { return patienceEnd_ && motions_.size() >= *patienceEnd_; }

bool PKpiece::stalled() {
  if (settings_.treeMotions > 0 && motions_.size() - treeStart_ >= settings_.treeMotions)
    return true;
  if (treeBestRank_ <= progressRank_ - kProgress) {
    progressRank_ = treeBestRank_;
    expansionsSinceProgress_ = 0;
    return false;
  }
  if (settings_.restartAfter == 0) return false;
  return ++expansionsSinceProgress_ >= settings_.restartAfter;
}

void PKpiece::tallyBrokenRule(const NominalRun& run, bool steered) {
  if (run.stoppedBy == physics::Violation::None) return;
  candidateFailures_.addViolation(run.stoppedBy, run.stoppedOn);
  if (steered) steeredFailures_.addViolation(run.stoppedBy, run.stoppedOn);
}

void PKpiece::startAfresh() {
  // How near the tree got is what later trees' push angles learn from.
  steering_.pushAngles().record(restarts_, treeLearningRank_);
  ++restarts_;
  startTree(restarts_);
}

void PKpiece::startTree(std::size_t tree) {
  steering_.setTree(tree);
  grid_.clear();
  cells_.clear();
  treeBestRank_ = std::numeric_limits<double>::infinity();
  treeLearningRank_ = std::numeric_limits<double>::infinity();
  goalStarts_.clear();
  iteration_ = 1;  // cells' ages count from the new tree's first expansion, as the first tree's
  beliefMeanSum_ = 0.0;
  plantRoot();
}

void PKpiece::getPlannerData(ompl::base::PlannerData& data) const {
  Planner::getPlannerData(data);
  for (const auto& motion : motions_) {
    const BeliefVertex vertex(motion->state, selectionBelief(*motion));
    if (motion->parent)
      data.addEdge(BeliefVertex(motion->parent->state, selectionBelief(*motion->parent)), vertex);
    else
      data.addStartVertex(vertex);
  }
}

}  // namespace kautham::planners

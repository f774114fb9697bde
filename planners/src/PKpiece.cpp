#include "kautham/planners/PKpiece.h"

#include <algorithm>
#include <cmath>

#include <ompl/base/PlannerData.h>
#include <ompl/control/PathControl.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>
#include <ompl/datastructures/PDF.h>

#include "kautham/physics/WorldStateSpace.h"
#include "kautham/planners/BeliefVertex.h"

namespace kautham::planners {

namespace {
// Cell scores as in KPIECE: an expansion that adds a motion keeps most of the cell's score,
// one that fails halves it, so cells that stop producing fade.
constexpr double kGoodScoreFactor = 0.9;
constexpr double kBadScoreFactor = 0.45;
constexpr std::size_t kNearestKept = 30;  // motions nearest the goal kept for the goal bias
}  // namespace

struct PKpiece::Motion {
  ompl::base::State* state = nullptr;  ///< the state at the motion's end
  std::vector<double> control;
  unsigned steps = 0;
  Motion* parent = nullptr;
  double belief = 1.0;
  std::shared_ptr<const ObjectPoseBelief> poses;
  double goalDistance = 0.0;
  CellData* cell = nullptr;
  bool reachesGoal = false;  ///< in the goal, and enough of its particles were too
};

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
      grid_(context.projection().getDimension()) {
  specs_.approximateSolutions = true;
  scratch_ = si_->allocState();
  grid_.onCellUpdate(&PKpiece::computeImportance, this);
  addPlannerProgressProperty("cells INTEGER", [this] { return std::to_string(cells_.size()); });
  addPlannerProgressProperty("candidates INTEGER",
                             [this] { return std::to_string(candidateCount_); });
  addPlannerProgressProperty("particles INTEGER",
                             [this] { return std::to_string(evaluator_.particleCount()); });
  addPlannerProgressProperty("mean_solution_belief REAL", [this] {
    if (solutionBeliefs_.empty()) return std::string("nan");
    double sum = 0.0;
    for (double b : solutionBeliefs_) sum += b;
    return std::to_string(sum / solutionBeliefs_.size());
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
  nearest_.clear();
  iteration_ = 1;
  beliefMeanSum_ = 0.0;
  candidateCount_ = 0;
  solutionBeliefs_.clear();
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
  data.beliefSum += motion->belief;
  beliefMeanSum_ += data.meanBelief();
  motion->cell = &data;

  nearest_.push_back(motion);
  std::sort(nearest_.begin(), nearest_.end(),
            [](const Motion* a, const Motion* b) { return a->goalDistance < b->goalDistance; });
  if (nearest_.size() > kNearestKept) nearest_.pop_back();
}

PKpiece::Motion* PKpiece::nearGoalMotion() {
  ompl::PDF<Motion*> pdf;
  for (Motion* m : nearest_) pdf.add(m, 1.0 / (m->goalDistance + 0.01));
  return pdf.sample(rng_.uniform01());
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
    if (m->belief > best + 1e-12) {
      best = m->belief;
      ties.assign(1, m);
    } else if (std::abs(m->belief - best) <= 1e-12) {
      ties.push_back(m);
    }
  }
  return ties[static_cast<std::size_t>(rng_.uniformInt(0, static_cast<int>(ties.size()) - 1))];
}

PKpiece::Motion* PKpiece::selectMotion() {
  if (!nearest_.empty() && rng_.uniform01() < settings_.goalBias) return nearGoalMotion();
  const bool exterior = grid_.countExternal() > 0 &&
                        (grid_.countInternal() == 0 || rng_.uniform01() < settings_.borderFraction);
  Grid::Cell* cell = exterior ? grid_.topExternal() : grid_.topInternal();
  cell->data->selections += 1;
  return selectInCell(*cell->data);
}

std::vector<PKpiece::Candidate> PKpiece::sampleCandidates(const Motion& from) {
  const auto& si = context_.spaceInformation();
  const unsigned minSteps = si->getMinControlDuration();
  const unsigned maxSteps = si->getMaxControlDuration();
  const std::size_t dimension = si->getControlSpace()->getDimension();
  const double* start = physics::WorldStateSpace::values(from.state);
  const unsigned particles = settings_.uncertainty ? settings_.particles : 0;
  std::vector<Candidate> valid;
  for (unsigned c = 0; c < settings_.candidates; ++c) {
    Candidate candidate;
    candidate.control.resize(dimension);
    for (double& u : candidate.control) u = rng_.uniformReal(-1.0, 1.0);
    const unsigned steps = static_cast<unsigned>(
        rng_.uniformInt(static_cast<int>(minSteps), static_cast<int>(maxSteps)));
    candidate.run = evaluator_.runNominal(start, candidate.control.data(), steps);
    ++candidateCount_;
    if (candidate.run.steps == 0) continue;  // invalid from its first step
    // Without uncertainty the nominal run is the only particle (the paper's pKP column).
    candidate.verdict = particles == 0 ? evaluator_.judgeNominal(start, candidate.run.end.data())
                                       : evaluator_.runParticles(start, candidate.control.data(),
                                                                 candidate.run.steps, *from.poses,
                                                                 particles, nextStreamSeed());
    valid.push_back(std::move(candidate));
  }
  return valid;
}

bool PKpiece::reachesGoal(const Candidate& c) const {
  return c.run.reachedGoal && c.verdict.goal >= settings_.goalConfidence;
}

const PKpiece::Candidate* PKpiece::chooseCandidate(const std::vector<Candidate>& valid) {
  if (valid.empty()) return nullptr;
  // A candidate that reaches the goal ends the search: the most robust of those is kept.
  const Candidate* best = nullptr;
  for (const Candidate& c : valid)
    if (reachesGoal(c) && (!best || c.verdict.belief() > best->verdict.belief())) best = &c;
  if (best) return best;
  if (rng_.uniform01() < settings_.randomCandidate)
    return &valid[static_cast<std::size_t>(rng_.uniformInt(0, static_cast<int>(valid.size()) - 1))];
  for (const Candidate& c : valid)
    if (!best || c.verdict.belief() > best->verdict.belief()) best = &c;
  return best;
}

PKpiece::Motion* PKpiece::expand(Motion* from) {
  const std::vector<Candidate> valid = sampleCandidates(*from);
  const Candidate* chosen = chooseCandidate(valid);
  if (!chosen) return nullptr;
  const double* start = physics::WorldStateSpace::values(from->state);
  const auto endPoses = from->poses->afterMotion(
      evaluator_.objectBodies(), start, chosen->run.end.data(), chosen->verdict.ends, fitRng_);
  // As KPIECE does, the kept motion is cut where its end effector changes cell: each piece is
  // a motion of the tree, so one expansion can cover several cells.
  // Pieces before the end carry the parent's pose distribution while no object has moved yet,
  // and the end's once one has (the particles tell only how the motion ends).
  const std::vector<std::vector<double>>& states = chosen->run.states;
  Motion* parent = from;
  unsigned pieceStart = 0;
  for (unsigned i = 0; i < states.size(); ++i) {
    const bool last = i + 1 == states.size();
    if (!last && cellOf(states[i]) == cellOf(states[i + 1])) continue;
    const bool untouched = !last && !objectsMoved(start, states[i].data());
    parent = addPiece(parent, *chosen, states[i], i + 1 - pieceStart,
                      untouched ? from->poses : endPoses);
    pieceStart = i + 1;
  }
  return parent;
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
                                   std::shared_ptr<const ObjectPoseBelief> poses) {
  auto motion = std::make_unique<Motion>();
  motion->state = si_->allocState();
  double* values = physics::WorldStateSpace::values(motion->state);
  std::copy(end.begin(), end.end(), values);
  motion->control = chosen.control;
  motion->steps = steps;
  motion->parent = parent;
  motion->belief = chosen.verdict.belief();
  motion->goalDistance = context_.goal().distance(values);
  motion->poses = std::move(poses);
  motion->reachesGoal = reachesGoal(chosen) && &end == &chosen.run.states.back();
  Motion* raw = motion.get();
  motions_.push_back(std::move(motion));
  addMotion(raw);
  return raw;
}

void PKpiece::recordSolution(const Motion* end, bool exact, double distance) {
  std::vector<const Motion*> chain;
  for (const Motion* m = end; m; m = m->parent) chain.push_back(m);
  std::reverse(chain.begin(), chain.end());
  auto path = std::make_shared<ompl::control::PathControl>(si_);
  auto* csi = static_cast<ompl::control::SpaceInformation*>(si_.get());
  const double stepSize = csi->getPropagationStepSize();
  solutionBeliefs_.clear();
  path->append(chain.front()->state);
  for (std::size_t i = 1; i < chain.size(); ++i) {
    ompl::control::Control* control = csi->allocControl();
    std::copy(chain[i]->control.begin(), chain[i]->control.end(),
              control->as<ompl::control::RealVectorControlSpace::ControlType>()->values);
    path->append(chain[i]->state, control, chain[i]->steps * stepSize);
    csi->freeControl(control);
    solutionBeliefs_.push_back(chain[i]->belief);
  }
  pdef_->addSolutionPath(path, !exact, distance, getName());
}

ompl::base::PlannerStatus PKpiece::solve(const ompl::base::PlannerTerminationCondition& ptc) {
  checkValidity();
  if (motions_.empty()) {
    auto root = std::make_unique<Motion>();
    root->state = si_->allocState();
    si_->copyState(root->state, pdef_->getStartState(0));
    const double* start = physics::WorldStateSpace::values(root->state);
    root->goalDistance = context_.goal().distance(start);
    root->poses = settings_.uncertainty
                      ? ObjectPoseBelief::initial(context_.layout(), evaluator_.sampler(), start)
                      : std::make_shared<const ObjectPoseBelief>();
    Motion* raw = root.get();
    motions_.push_back(std::move(root));
    addMotion(raw);
    grid_.updateAll();
  }
  while (!ptc) {
    Motion* from = selectMotion();
    CellData* cell = from->cell;
    Motion* added = expand(from);
    cell->score *= added ? kGoodScoreFactor : kBadScoreFactor;
    ++iteration_;
    grid_.updateAll();  // beliefs are normalised over all cells: every importance changes
    if (added && added->reachesGoal) {
      recordSolution(added, true, added->goalDistance);
      return ompl::base::PlannerStatus::EXACT_SOLUTION;
    }
  }
  if (nearest_.empty() || nearest_.front()->parent == nullptr)
    return ompl::base::PlannerStatus::TIMEOUT;
  recordSolution(nearest_.front(), false, nearest_.front()->goalDistance);
  return ompl::base::PlannerStatus::APPROXIMATE_SOLUTION;
}

void PKpiece::getPlannerData(ompl::base::PlannerData& data) const {
  Planner::getPlannerData(data);
  for (const auto& motion : motions_) {
    const BeliefVertex vertex(motion->state, motion->belief);
    if (motion->parent)
      data.addEdge(BeliefVertex(motion->parent->state, motion->parent->belief), vertex);
    else
      data.addStartVertex(vertex);
  }
}

}  // namespace kautham::planners

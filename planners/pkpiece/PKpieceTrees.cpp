// p-KPIECE's trees grown in processes of their own (parallel_trees): a search that starts its
// tree afresh, again and again on the dense scenes, uses every core, and a fixed seed gives the
// same plan at any --threads (docs/planners.md, "Trees grown in parallel").

#include <algorithm>
#include <array>
#include <cstdint>
#include <exception>
#include <stdexcept>
#include <vector>

#include <ompl/control/spaces/RealVectorControlSpace.h>

#include "PKpieceMotion.h"
#include "ProcessIo.h"
#include "kautham/core/Random.h"
#include "kautham/physics/WorldStateSpace.h"
#include "kautham/planners/pkpiece/PKpiece.h"
#include "kautham/planners/pkpiece/TreeProcesses.h"
#include "kautham/planners/pkpiece/TreesInOrder.h"

namespace kautham::planners {

using namespace process_io;

namespace {

// More values than any state or control has: a corrupt message.
constexpr std::size_t kMaxValues = 1u << 20;
constexpr std::uint64_t kMaxMotions = 1u << 24;

void putTally(Packer& pack, const FailureTally& tally) {
  const std::vector<FailureTally::Entry> entries = tally.entries();
  pack.put(std::uint64_t{entries.size()});
  for (const FailureTally::Entry& e : entries) {
    pack.put(static_cast<std::uint64_t>(e.violation));
    pack.put(std::uint64_t{e.body ? *e.body + 1 : 0});
    pack.put(e.count);
  }
}

FailureTally getTally(Unpacker& unpack) {
  FailureTally tally;
  const std::uint64_t entries = unpack.u64();
  if (entries > kMaxValues) throw std::runtime_error("p-KPIECE: a tree's result is corrupt");
  for (std::uint64_t i = 0; i < entries; ++i) {
    FailureTally::Entry e;
    const std::uint64_t violation = unpack.u64();
    if (violation >= physics::kViolationKinds)
      throw std::runtime_error("p-KPIECE: a tree's result is corrupt");
    e.violation = static_cast<physics::Violation>(violation);
    if (const std::uint64_t body = unpack.u64(); body > 0) e.body = body - 1;
    e.count = unpack.u64();
    tally.add(e);
  }
  return tally;
}

}  // namespace

std::array<std::uint64_t*, 12> PKpiece::searchCounts() {
  // One list for packing a tree's counts and adding them up: the two stay in step.
  return {&candidateCount_,   &goalCandidates_, &steeredCandidates_,
          &steeredValid_,     &steeredKept_,    &keptCandidates_,
          &confirmations_,    &verifications_,  &verificationRejections_,
          &verificationRuns_, &grownMotions_,   &coresLent_};
}

void PKpiece::reseedForTree(std::size_t tree) {
  // Tree 0 draws on from the planner's own streams, as the first tree does without
  // parallel_trees: a search that ends in its first tree gives the same plan either way.
  if (tree == 0) return;
  const std::uint64_t seed = core::runSeed(treeSeedBase_, tree);
  rng_.setLocalSeed(static_cast<std::uint_fast32_t>(seed & 0xffffffffULL));
  fitRng_.seed(seed);
  streamBase_ = (seed >> 33) << 20;
  streamCounter_ = 0;
  verifier_.reseed(streamBase_ ^ 0x5645524946590000ULL);
}

std::vector<unsigned char> PKpiece::growTreeForSearch(
    std::size_t tree, TreeProcesses::LentCores& lent,
    const ompl::base::PlannerTerminationCondition& ptc) {
  // This process is a copy of the planner as the search began (with the trees settled since):
  // it counts only its own tree's work.
  reseedForTree(tree);
  lentCores_ = &lent;
  verifier_.beforeEachBatch([this] { useLentCores(); });
  // The paths adopted from the trees taken in before this one: how many depends on --threads,
  // so the tree starts without them.
  for (auto& motion : motions_) si_->freeState(motion->state);
  motions_.clear();
  verified_.clear();
  closest_ = nullptr;
  resetCounters();
  const physics::PropagationCounters before = context_.propagator().counters();
  startTree(tree);
  restarts_ = 0;  // the search counts the trees it takes in
  // The caller's condition may report progress or count its checks: that is the search's own
  // process's business. A tree stops at the time limit (and at the condition when there is none).
  const ompl::base::PlannerTerminationCondition atDeadline([this] { return pastDeadline(); });
  const TreeEnd end = growTree(deadline_ ? atDeadline : ptc);
  const physics::PropagationCounters after = context_.propagator().counters();

  std::vector<unsigned char> bytes;
  Packer pack(bytes);
  pack.put(static_cast<std::uint64_t>(end));
  pack.put(std::uint64_t{tree});
  pack.put(treeLearningRank_);
  for (std::uint64_t* count : searchCounts()) pack.put(*count);
  for (const std::uint64_t count :
       {steering_.jacobianAims(), evaluator_.particleCount(), evaluator_.certainEarly(),
        after.propagations - before.propagations, after.physicsSteps - before.physicsSteps})
    pack.put(count);
  pack.put(bestGoalConfidence_);
  putTally(pack, evaluator_.particleFailures());
  putTally(pack, candidateFailures_);
  putTally(pack, steeredFailures_);

  // The plan, or the motion nearest the goal: root first.
  const Motion* last = end == TreeEnd::Verified       ? verified_.back().end
                       : closest_ && closest_->parent ? closest_
                                                      : nullptr;
  pack.put(std::uint64_t{end == TreeEnd::Verified ? verified_.back().runs : 0u});
  pack.put(std::uint64_t{end == TreeEnd::Verified ? verified_.back().successes : 0u});
  // Where the plan's estimate is to be measured from (measureInPlanner).
  const std::optional<PlanVerifier::Streams> toMeasure =
      end == TreeEnd::Verified ? verified_.back().toMeasure : std::nullopt;
  pack.put(std::uint64_t{toMeasure ? 1u : 0u});
  pack.put(toMeasure ? toMeasure->seedBase : std::uint64_t{0});
  pack.put(toMeasure ? toMeasure->nextRun : std::uint64_t{0});
  std::vector<const Motion*> chain;
  for (const Motion* m = last; m; m = m->parent) chain.push_back(m);
  std::reverse(chain.begin(), chain.end());
  pack.put(std::uint64_t{chain.size()});
  const unsigned stateSize = si_->getStateDimension();
  for (const Motion* m : chain) {
    const double* values = physics::WorldStateSpace::values(m->state);
    pack.put(std::vector<double>(values, values + stateSize));
    pack.put(m->control);
    pack.put(std::uint64_t{m->steps});
    pack.put(std::uint64_t{m->expansion});
    pack.put(m->belief);
    pack.put(m->pathBelief);
    pack.put(m->goalDistance);
    pack.put(std::uint64_t{m->reachesGoal ? 1u : 0u});
    pack.put(m->successEstimate);
  }
  return bytes;
}

PKpiece::TreeEnd PKpiece::settleTree(const std::vector<unsigned char>& result) {
  Unpacker unpack(result);
  const std::uint64_t endValue = unpack.u64();
  if (endValue > static_cast<std::uint64_t>(TreeEnd::Stopped))
    throw std::runtime_error("p-KPIECE: a tree's result is corrupt");
  const auto end = static_cast<TreeEnd>(endValue);
  const std::uint64_t tree = unpack.u64();
  // How near the tree got is what later trees' push angles learn from.
  steering_.pushAngles().record(tree, unpack.real());
  for (std::uint64_t* count : searchCounts()) *count += unpack.u64();
  steering_.addJacobianAims(unpack.u64());
  const std::uint64_t particles = unpack.u64();
  const std::uint64_t certainEarly = unpack.u64();
  physics::PropagationCounters work;
  work.propagations = unpack.u64();
  work.physicsSteps = unpack.u64();
  context_.propagator().addCounters(work);
  bestGoalConfidence_ = std::max(bestGoalConfidence_, unpack.real());
  evaluator_.addCounts(particles, certainEarly, getTally(unpack));
  for (FailureTally* tally : {&candidateFailures_, &steeredFailures_})
    for (const FailureTally::Entry& entry : getTally(unpack).entries()) tally->add(entry);

  VerifiedPlan plan;
  plan.runs = static_cast<unsigned>(unpack.u64());
  plan.successes = static_cast<unsigned>(unpack.u64());
  const bool measureHere = unpack.u64() != 0;
  PlanVerifier::Streams toMeasure;
  toMeasure.seedBase = unpack.u64();
  toMeasure.nextRun = unpack.u64();
  if (measureHere) plan.toMeasure = toMeasure;
  const std::uint64_t length = unpack.u64();
  if (length > kMaxMotions) throw std::runtime_error("p-KPIECE: a tree's result is corrupt");
  const unsigned stateSize = si_->getStateDimension();
  Motion* parent = nullptr;
  for (std::uint64_t i = 0; i < length; ++i) {
    const std::vector<double> values = unpack.reals(kMaxValues);
    if (values.size() != stateSize)
      throw std::runtime_error("p-KPIECE: a tree's result is corrupt");
    motions_.push_back(std::make_unique<Motion>());  // owned before anything else can throw
    Motion* motion = motions_.back().get();
    motion->state = si_->allocState();
    std::copy(values.begin(), values.end(), physics::WorldStateSpace::values(motion->state));
    motion->control = unpack.reals(kMaxValues);
    motion->steps = static_cast<unsigned>(unpack.u64());
    motion->expansion = static_cast<unsigned>(unpack.u64());
    motion->belief = unpack.real();
    motion->pathBelief = unpack.real();
    motion->goalDistance = unpack.real();
    motion->reachesGoal = unpack.u64() != 0;
    motion->successEstimate = unpack.real();
    motion->parent = parent;
    parent = motion;
  }
  if (end == TreeEnd::Verified) {
    if (!parent) throw std::runtime_error("p-KPIECE: a tree's result is corrupt");
    plan.end = parent;
    verified_.push_back(plan);
  } else if (parent && (!closest_ || parent->goalDistance < closest_->goalDistance)) {
    closest_ = parent;
  }
  return end;
}

ompl::base::PlannerStatus PKpiece::solveTreeByTree(
    const ompl::base::PlannerTerminationCondition& ptc) {
  TreeProcesses trees(treeProcesses_,
                      [this, &ptc](std::size_t tree, TreeProcesses::LentCores& lent) {
                        return growTreeForSearch(tree, lent, ptc);
                      });
  TreeOrder order;
  order.ends = [](const TreeOrder::Result& result) {
    Unpacker peek(result);
    return peek.u64() == static_cast<std::uint64_t>(TreeEnd::Verified);
  };
  // A tree the time stopped is passed over: the plan is the first verified one in order.
  order.takeIn = [this](const TreeOrder::Result& result) {
    return settleTree(result) == TreeEnd::Verified;
  };
  order.stop = [this, &ptc] { return ptc() || pastDeadline(); };
  // A tree whose push angles are learned starts once the trees they learn from are taken in.
  order.takenInBefore = [this](std::size_t tree) {
    return static_cast<std::size_t>(steering_.pushAngles().treesBefore(tree));
  };
  const TreesTaken taken = takeTreesInOrder(trees, order);
  discardedTrees_ += taken.started - taken.takenIn;
  restarts_ += taken.takenIn > 0 ? taken.takenIn - 1 : 0;
  for (VerifiedPlan& plan : verified_)
    if (plan.toMeasure) measureInPlanner(plan);
  return finish();
}

void PKpiece::useLentCores() {
  if (!lentCores_) return;
  // A tree that holds up the search's end grows alone: a later tree ended it, and the core that
  // grew that one would wait idle. The workers give the same results as this process alone.
  if (const unsigned more = lentCores_->collect()) {
    coresLent_ += more;
    try {
      evaluator_.useWorkers(evaluator_.threads() + more);
    } catch (const std::exception&) {
      // No process to spare (fork failed): a loan is help, not a need; the tree goes on inline.
      evaluator_.useWorkers(1);
    }
  }
}

void PKpiece::measureInPlanner(VerifiedPlan& plan) {
  // The trees' processes are gone (takeTreesInOrder stops them): their cores run the estimate.
  evaluator_.useWorkers(treeProcesses_);
  verifier_.resume(*plan.toMeasure);
  plan.toMeasure.reset();
  const VerificationResult fresh = measureEstimate(plan.end);
  plan.runs += fresh.runs;
  plan.successes += fresh.successes;
  evaluator_.useWorkers(1);
}

}  // namespace kautham::planners

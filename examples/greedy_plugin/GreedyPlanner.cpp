// A planner plugin for kautham in one file: "Greedy", a small control planner.
//
// It grows a tree of motions over the physics. Each iteration picks a motion to grow from (with
// probability goal_bias the one that ended nearest the goal, else one at random), tries
// `samples` random controls held for a random number of steps from its end state, and keeps the
// one that ends nearest the goal. It stops when a motion ends in the goal region.
//
// Build it against an installed kautham (see CMakeLists.txt next to this file and
// docs/plugins.md), then: kautham plan problems/pusher_cans_5.xml --planner Greedy
//                              --plugin build/libkautham_greedy.so

#include <limits>
#include <memory>
#include <vector>

#include <ompl/base/PlannerData.h>
#include <ompl/control/PathControl.h>
#include <ompl/util/RandomNumbers.h>

#include <kautham/planners/Plugin.h>

namespace {

/// Greedy's settings; each field's parameter is declared once, in parameters().
struct GreedySettings {
  double goalBias;   ///< probability of growing the motion nearest the goal
  unsigned samples;  ///< random controls tried per iteration

  static const kautham::core::SettingsParameters<GreedySettings>& parameters() {
    using kautham::core::Parameter;
    static const auto table =
        kautham::core::SettingsParameters<GreedySettings>()
            .add(&GreedySettings::goalBias, kautham::planners::goalBiasParameter(0.3))
            .add(&GreedySettings::samples, Parameter::integer("samples")
                                               .byDefault(4)
                                               .range(1, 100)
                                               .describe("random controls tried per iteration; "
                                                         "the one ending nearest the goal is kept")
                                               .alias("Samples"));
    return table;
  }
};

class Greedy : public ompl::base::Planner {
 public:
  Greedy(const ompl::control::SpaceInformationPtr& si, const GreedySettings& settings)
      : ompl::base::Planner(si, "Greedy"), siPtr_(si), si_(si.get()), settings_(settings) {}

  ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition& ptc) override {
    checkValidity();
    const ompl::base::Goal* goal = pdef_->getGoal().get();
    if (motions_.empty())
      while (const ompl::base::State* start = pis_.nextStart()) {
        auto root = std::make_unique<Motion>(si_);
        si_->copyState(root->state, start);
        goal->isSatisfied(root->state, &root->distance);
        motions_.push_back(std::move(root));
      }
    if (motions_.empty()) return ompl::base::PlannerStatus::INVALID_START;

    ompl::control::Control* control = si_->allocControl();
    ompl::base::State* end = si_->allocState();
    Motion* solution = nullptr;
    while (!ptc && solution == nullptr) {
      Motion* from =
          rng_.uniform01() < settings_.goalBias
              ? nearest()
              : motions_[rng_.uniformInt(0, static_cast<int>(motions_.size()) - 1)].get();
      std::unique_ptr<Motion> best;
      for (unsigned i = 0; i < settings_.samples; ++i) {
        controlSampler_->sample(control);
        const unsigned steps =
            static_cast<unsigned>(rng_.uniformInt(static_cast<int>(si_->getMinControlDuration()),
                                                  static_cast<int>(si_->getMaxControlDuration())));
        const unsigned valid = si_->propagateWhileValid(from->state, control, steps, end);
        if (valid == 0) continue;  // the first step already broke a constraint
        double distance = std::numeric_limits<double>::infinity();
        const bool reached = goal->isSatisfied(end, &distance);
        if (best && !reached && distance >= best->distance) continue;
        best = std::make_unique<Motion>(si_);
        si_->copyState(best->state, end);
        si_->copyControl(best->control, control);
        best->steps = valid;
        best->parent = from;
        best->distance = distance;
        best->reached = reached;
        if (reached) break;
      }
      if (!best) continue;
      if (best->reached) solution = best.get();
      motions_.push_back(std::move(best));
    }
    si_->freeState(end);
    si_->freeControl(control);

    Motion* last = solution ? solution : nearest();
    if (last->parent == nullptr) return ompl::base::PlannerStatus::TIMEOUT;
    std::vector<const Motion*> chain;
    for (const Motion* m = last; m != nullptr; m = m->parent) chain.push_back(m);
    auto path = std::make_shared<ompl::control::PathControl>(siPtr_);
    path->append(chain.back()->state);
    for (auto it = chain.rbegin() + 1; it != chain.rend(); ++it)
      path->append((*it)->state, (*it)->control, (*it)->steps * si_->getPropagationStepSize());
    pdef_->addSolutionPath(path, solution == nullptr, last->distance, getName());
    return solution ? ompl::base::PlannerStatus::EXACT_SOLUTION
                    : ompl::base::PlannerStatus::APPROXIMATE_SOLUTION;
  }

  void setup() override {
    ompl::base::Planner::setup();
    controlSampler_ = si_->allocControlSampler();
  }

  void clear() override {
    ompl::base::Planner::clear();
    motions_.clear();
  }

  void getPlannerData(ompl::base::PlannerData& data) const override {
    ompl::base::Planner::getPlannerData(data);
    for (const auto& motion : motions_) {
      if (motion->parent == nullptr)
        data.addStartVertex(ompl::base::PlannerDataVertex(motion->state));
      else
        data.addEdge(ompl::base::PlannerDataVertex(motion->parent->state),
                     ompl::base::PlannerDataVertex(motion->state));
    }
  }

 private:
  /// A control held for some steps from the parent's end state, and the state it reached.
  struct Motion {
    explicit Motion(ompl::control::SpaceInformation* si)
        : si(si), state(si->allocState()), control(si->allocControl()) {}
    ~Motion() {
      si->freeState(state);
      si->freeControl(control);
    }
    Motion(const Motion&) = delete;
    Motion& operator=(const Motion&) = delete;
    ompl::control::SpaceInformation* si;
    ompl::base::State* state;
    ompl::control::Control* control;
    unsigned steps = 0;
    const Motion* parent = nullptr;
    double distance = std::numeric_limits<double>::infinity();  ///< to the goal, at the end
    bool reached = false;
  };

  Motion* nearest() const {
    Motion* best = motions_.front().get();
    for (const auto& m : motions_)
      if (m->distance < best->distance) best = m.get();
    return best;
  }

  ompl::control::SpaceInformationPtr siPtr_;
  ompl::control::SpaceInformation* si_;
  GreedySettings settings_;
  ompl::control::ControlSamplerPtr controlSampler_;
  ompl::RNG rng_;
  std::vector<std::unique_ptr<Motion>> motions_;
};

}  // namespace

KAUTHAM_PLANNER_PLUGIN(registry) {
  registry.add(kautham::planners::plannerEntry<GreedySettings>(
      "Greedy",
      "example plugin: grows the tree from the motion nearest the goal (or a random one), "
      "keeping the best of a few random controls",
      GreedySettings::parameters(),
      [](const GreedySettings& settings, kautham::physics::PlanningContext& context) {
        return ompl::base::PlannerPtr(
            std::make_shared<Greedy>(context.spaceInformation(), settings));
      }));
}

// Physics throughput: how fast ODE steps our scenes, and how much of that speed the planner's
// inner loop (PhysicsPropagator::propagate + WorldValidityChecker::check, chained from state to
// state) keeps. Scenes are problems/pusher_cans_5.xml with 5, 20 and 40 cans, where the pusher
// sweeps the table with a fixed control sequence that pushes cans, and the arm problems
// (tests/data/kuka_table.xml, tests/data/yumi_table.xml, problems/kuka_cans_*.xml), where every
// arm joint turns forth and back in turn. See docs/performance.md.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <ompl/control/spaces/RealVectorControlSpace.h>
#include <CLI/CLI.hpp>

#include "kautham/core/ProblemLoader.h"
#include "kautham/physics/OdeLibrary.h"
#include "kautham/physics/PlanningContext.h"

namespace {

using kautham::core::ObjectInstance;
using kautham::core::ObjectRole;
using kautham::core::Problem;
using kautham::physics::BodyRole;
using kautham::physics::PlanningContext;
using kautham::physics::PropagationSettings;
using kautham::physics::Violation;
using kautham::physics::World;
using kautham::physics::WorldLayout;
using kautham::physics::WorldStateSpace;
using Clock = std::chrono::steady_clock;

// ---------------------------------------------------------------------------------------------
// Scenes

constexpr double kCanRadius = 0.033;
constexpr double kCanHeight = 0.811;  ///< centre of a can standing on the table top (z = 0.75)
constexpr double kGap = 0.02;         ///< least free space around every can
constexpr double kGlassX = 0.0;
constexpr double kGlassY = 0.22;
constexpr double kGlassRadius = 0.04;
// The gripper at its start (palm and fingers, see planar_pusher.urdf): x in [-0.07, 0.07],
// y in [-0.31, -0.22].
constexpr double kGripperMaxX = 0.07;
constexpr double kGripperMaxY = -0.22;
constexpr double kGripperMinY = -0.31;
// The grid: 9 columns 11 cm apart at |x| <= 0.44 (inside the pusher's workspace, |x| <= 0.45),
// 6 rows 10 cm apart from y = -0.16 to 0.34 (the back row 2.7 cm inside the table's edge):
// gaps of 4.4 cm and 3.4 cm. Columns are wider apart than the 2 cm gap needs: with the gripper
// centred on a column, that column's can sits between the fingers (inner edges at +-6 cm) and
// the next columns' cans clear the fingers (outer edges at +-7 cm) by 7 mm, so a push moves
// one column straight ahead instead of shoving cans sideways into the glass.
constexpr int kColumns = 9;
constexpr int kRows = 6;
constexpr double kColumnPitch = 0.11;
constexpr double kRowPitch = 0.10;
constexpr double kFirstRowY = -0.16;
constexpr double kOrderFromY = -0.1;

struct Slot {
  double x = 0.0;
  double y = 0.0;
};

/// Can positions on the grid, off the glass and off the pusher by at least the gap, nearest
/// first to (0, kOrderFromY): the small scene stands in front of the pusher, the larger ones
/// add rings around it and around the glass (each scene is the smaller one plus more cans).
std::vector<Slot> canSlots() {
  std::vector<Slot> slots;
  for (int r = 0; r < kRows; ++r) {
    for (int c = 0; c < kColumns; ++c) {
      const Slot s{(c - kColumns / 2) * kColumnPitch, kFirstRowY + r * kRowPitch};
      const double toGlass = std::hypot(s.x - kGlassX, s.y - kGlassY);
      if (toGlass < kGlassRadius + kCanRadius + kGap) continue;
      const double dx = std::max(0.0, std::abs(s.x) - kGripperMaxX);
      const double dy = std::max({0.0, s.y - kGripperMaxY, kGripperMinY - s.y});
      if (std::hypot(dx, dy) < kCanRadius + kGap) continue;
      slots.push_back(s);
    }
  }
  const auto key = [](const Slot& s) { return std::hypot(s.x, s.y - kOrderFromY); };
  std::stable_sort(slots.begin(), slots.end(),
                   [&](const Slot& a, const Slot& b) { return key(a) < key(b); });
  return slots;
}

/// The problem file with its cans replaced by `cans` copies of its first can, named can1..canN.
Problem makeScene(const Problem& base, int cans) {
  const auto isCan = [](const ObjectInstance& o) { return o.role == ObjectRole::Movable; };
  const auto can = std::find_if(base.objects.begin(), base.objects.end(), isCan);
  if (can == base.objects.end()) throw std::runtime_error("the problem has no movable object");
  const ObjectInstance canTemplate = *can;

  const std::vector<Slot> slots = canSlots();
  if (cans < 1 || static_cast<std::size_t>(cans) > slots.size())
    throw std::runtime_error("between 1 and " + std::to_string(slots.size()) +
                             " cans fit on the table, not " + std::to_string(cans));
  Problem scene = base;
  scene.name = base.name + "_x" + std::to_string(cans);
  scene.objects.erase(std::remove_if(scene.objects.begin(), scene.objects.end(), isCan),
                      scene.objects.end());
  for (int i = 0; i < cans; ++i) {
    ObjectInstance object = canTemplate;
    object.name = "can" + std::to_string(i + 1);
    object.home.position = {slots[i].x, slots[i].y, kCanHeight};
    scene.objects.push_back(std::move(object));
  }
  return scene;
}

// ---------------------------------------------------------------------------------------------
// The fixed sweep of the pusher

/// Joint velocity targets (x, y, yaw) held for a number of physics steps.
struct Segment {
  std::vector<double> velocities;  ///< joint velocity targets, one per actuator
  unsigned steps = 0;
};

/// The pusher drives along the columns of the can grid, centred on each: from the start
/// (0, -0.3) to x = -0.44, then for every column 20 cm forward (+y) and back (-y), and on to
/// the next column (+x). A push moves the column's first can by 10 cm, less than the free space
/// in front of it in every column (17 cm), so no can reaches the glass or the table's back
/// edge, and the gripper stays inside the workspace. Segments are whole multiples of 5 physics
/// steps, so they split into whole propagation steps.
std::vector<Segment> sweep() {
  constexpr double kForwardSpeed = 0.25;               // m/s, the y joint's limit
  constexpr unsigned kForwardSteps = 80;               // 20 cm at 0.01 s per step
  constexpr unsigned kShiftSteps = 45;                 // one column
  constexpr double kShiftSpeed = kColumnPitch / 0.45;  // 0.244 m/s
  constexpr int kSide = kColumns / 2;                  // columns each side of x = 0
  std::vector<Segment> segments{{{-kShiftSpeed, 0.0, 0.0}, kShiftSteps * kSide}};
  for (int column = -kSide; column <= kSide; ++column) {
    segments.push_back({{0.0, kForwardSpeed, 0.0}, kForwardSteps});
    segments.push_back({{0.0, -kForwardSpeed, 0.0}, kForwardSteps});
    if (column < kSide) segments.push_back({{kShiftSpeed, 0.0, 0.0}, kShiftSteps});
  }
  return segments;
}

/// The arm motion: each revolute joint in turn turns at 0.3 rad/s for 0.5 s, then back for
/// 0.5 s, every other joint held still; the fingers stay. The arm returns to its start
/// configuration after each joint, so it stays where its start state puts it (over the table).
std::vector<Segment> armMotion(const World& world) {
  constexpr double kSpeed = 0.3;   // rad/s
  constexpr unsigned kSteps = 50;  // physics steps each way (a multiple of 5)
  const auto& actuators = world.actuators();
  std::vector<Segment> segments;
  for (std::size_t j = 0; j < actuators.size(); ++j) {
    if (actuators[j].type == kautham::core::JointType::Prismatic) continue;
    for (double sign : {1.0, -1.0}) {
      Segment s{std::vector<double>(actuators.size(), 0.0), kSteps};
      s.velocities[j] = sign * kSpeed;
      segments.push_back(std::move(s));
    }
  }
  return segments;
}

unsigned totalSteps(const std::vector<Segment>& segments) {
  unsigned steps = 0;
  for (const Segment& s : segments) steps += s.steps;
  return steps;
}

// ---------------------------------------------------------------------------------------------
// Runs

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// What some sweeps did.
struct Work {
  double seconds = 0.0;
  unsigned long long steps = 0;    ///< physics steps
  unsigned long long calls = 0;    ///< propagate + check calls (none for raw stepping)
  unsigned long long invalid = 0;  ///< states the validity checker rejected

  Work& operator+=(const Work& other) {
    seconds += other.seconds;
    steps += other.steps;
    calls += other.calls;
    invalid += other.invalid;
    return *this;
  }
};

/// (a) World::step() in a loop (collision, QuickStep, contact cleanup) from the start state,
/// the controls set at the start of each segment. Only the loop is timed.
Work rawSweep(PlanningContext& context, const std::vector<Segment>& segments,
              std::vector<double>* finalState = nullptr) {
  World& world = context.world();
  world.writeState(context.startState().data());
  world.resetSolverSeed();
  world.takeEvents();
  Work work;
  const Clock::time_point start = Clock::now();
  for (const Segment& s : segments) {
    world.setJointVelocities(s.velocities.data());
    for (unsigned i = 0; i < s.steps; ++i) world.step();
  }
  work.seconds = secondsSince(start);
  work.steps = totalSteps(segments);
  if (finalState) {
    finalState->resize(context.layout().stateSize());
    world.readState(finalState->data());
  }
  return work;
}

/// A state a propagate call started from, with the call's control.
struct CallInput {
  std::vector<double> state;
  std::size_t segment = 0;
};

/// (b) and (d): the planner's inner loop. Each call propagates one propagation step of the
/// context from the previous call's result, then checks the result. The chain carries on
/// through invalid states (a planner would stop there) so that every run does the same work.
class ChainedRunner {
 public:
  explicit ChainedRunner(const PlanningContext& context)
      : context_(context),
        si_(context.spaceInformation()),
        from_(si_->allocState()),
        to_(si_->allocState()),
        control_(si_->allocControl()),
        stepsPerCall_(context.propagator().stepsFor(si_->getPropagationStepSize())) {}
  ~ChainedRunner() {
    si_->freeControl(control_);
    si_->freeState(from_);
    si_->freeState(to_);
  }
  ChainedRunner(const ChainedRunner&) = delete;
  ChainedRunner& operator=(const ChainedRunner&) = delete;

  unsigned stepsPerCall() const { return stepsPerCall_; }

  /// One sweep. `inputs` receives the state and control of every call (it costs time: only
  /// the warm-up sweep, whose time is not reported, records them).
  Work run(const std::vector<Segment>& segments, std::vector<double>* finalState = nullptr,
           std::vector<CallInput>* inputs = nullptr) {
    const auto& propagator = context_.propagator();
    const auto& checker = context_.validityChecker();
    const double duration = si_->getPropagationStepSize();
    double* controls = control_->as<ompl::control::RealVectorControlSpace::ControlType>()->values;
    const std::vector<double>& start = context_.startState();
    std::copy(start.begin(), start.end(), WorldStateSpace::values(from_));
    const unsigned long long stepsBefore = propagator.counters().physicsSteps;

    Work work;
    const Clock::time_point begin = Clock::now();
    for (std::size_t k = 0; k < segments.size(); ++k) {
      const Segment& s = segments[k];
      // The planner's controls that ask for the segment's joint velocities.
      const std::vector<double> u = propagator.mapping().controlsFor(s.velocities);
      std::copy(u.begin(), u.end(), controls);
      const unsigned calls = s.steps / stepsPerCall_;
      for (unsigned i = 0; i < calls; ++i) {
        if (inputs) {
          const double* values = WorldStateSpace::values(from_);
          inputs->push_back({std::vector<double>(values, values + start.size()), k});
        }
        propagator.propagate(from_, control_, duration, to_);
        if (checker.check(WorldStateSpace::values(to_)) != Violation::None) ++work.invalid;
        std::swap(from_, to_);
      }
      work.calls += calls;
    }
    work.seconds = secondsSince(begin);
    work.steps = propagator.counters().physicsSteps - stepsBefore;
    if (finalState) {
      const double* values = WorldStateSpace::values(from_);
      finalState->assign(values, values + start.size());
    }
    return work;
  }

 private:
  const PlanningContext& context_;
  ompl::control::SpaceInformationPtr si_;
  ompl::base::State* from_;
  ompl::base::State* to_;
  ompl::control::Control* control_;
  unsigned stepsPerCall_;
};

/// What a propagate + check call does besides its physics steps, timed alone on the states of
/// a chained sweep: PhysicsPropagator::propagate's sequence without the stepping loop (write the
/// state, set the controls, reset the seed, clear the events; read the state), then the
/// validity check. Seconds per call, from the best of a few rounds.
struct CallOverhead {
  double write = 0.0;  ///< writeState (with restoreGeomOrder) + controls + seed + events
  double read = 0.0;   ///< readState
  double check = 0.0;  ///< WorldValidityChecker::check
  double total() const { return write + read + check; }
};

CallOverhead measureCallOverhead(PlanningContext& context, const std::vector<Segment>& segments,
                                 const std::vector<CallInput>& inputs, double minSeconds) {
  World& world = context.world();
  const auto& checker = context.validityChecker();
  std::vector<double> out(context.layout().stateSize());
  CallOverhead best{1e9, 1e9, 1e9};
  const Clock::time_point begin = Clock::now();
  for (int round = 0; round < 5 || secondsSince(begin) < minSeconds; ++round) {
    Clock::time_point t = Clock::now();
    for (const CallInput& in : inputs) {
      world.writeState(in.state.data());
      world.setJointVelocities(segments[in.segment].velocities.data());
      world.resetSolverSeed();
      world.takeEvents();
    }
    best.write = std::min(best.write, secondsSince(t));
    t = Clock::now();
    for (std::size_t i = 0; i < inputs.size(); ++i) world.readState(out.data());
    best.read = std::min(best.read, secondsSince(t));
    t = Clock::now();
    // The checker lives in another library (no LTO), so the calls cannot be optimised away.
    for (const CallInput& in : inputs) checker.check(in.state.data());
    best.check = std::min(best.check, secondsSince(t));
  }
  const double n = static_cast<double>(inputs.size());
  return {best.write / n, best.read / n, best.check / n};
}

/// Movable objects whose centre ended more than 5 mm from where it started.
int movedCans(const PlanningContext& context, const std::vector<double>& finalState) {
  const WorldLayout& layout = context.layout();
  int moved = 0;
  for (std::size_t b = 0; b < layout.bodies.size(); ++b) {
    const Eigen::Vector3d from = WorldLayout::position(context.startState().data(), b);
    const Eigen::Vector3d to = WorldLayout::position(finalState.data(), b);
    if (layout.bodies[b].role == BodyRole::Movable && (to - from).norm() > 0.005) ++moved;
  }
  return moved;
}

/// The best (fastest) of the repetitions of one kind of run.
struct Rate {
  double stepsPerSecond = 0.0;
  double callsPerSecond = 0.0;

  void keepBest(const Work& work) {
    const double steps = static_cast<double>(work.steps) / work.seconds;
    if (steps > stepsPerSecond) {
      stepsPerSecond = steps;
      callsPerSecond = static_cast<double>(work.calls) / work.seconds;
    }
  }
};

struct SceneResult {
  std::string name;  ///< "5 cans", or the arm problem's file name
  int objects = 0;   ///< movable objects and target
  unsigned sweepsPerRepetition = 0;
  unsigned stepsPerCall = 0;  ///< physics steps per propagation step in (b)
  Rate raw;                   ///< (a)
  Rate propagate;             ///< (b)
  Rate propagate1;            ///< (d): one physics step per call
  CallOverhead overhead;
  int movedRaw = 0;
  int movedChained = 0;
  unsigned long long invalidPerSweep = 0;
  unsigned long long callsPerSweep = 0;
  std::vector<std::pair<int, double>> rawByIterations;  ///< (iterations, raw steps/s), arms only

  /// (c): time per physics step through propagate + check over time per raw step.
  double ratio() const { return raw.stepsPerSecond / propagate.stepsPerSecond; }
  double ratio1() const { return raw.stepsPerSecond / propagate1.stepsPerSecond; }
  /// The ratio that the timed overhead alone gives for `steps` physics steps per call.
  double overheadRatio(unsigned steps) const {
    return 1.0 + overhead.total() * raw.stepsPerSecond / steps;
  }
};

struct Options {
  std::vector<int> objects{5, 20, 40};
  double minSeconds = 0.7;
  int repetitions = 3;
  std::optional<int> maxContacts;
  bool arms = true;                         ///< also measure the arm problems
  std::vector<int> armIterations{20, 100};  ///< QuickStep iterations for the arms' raw stepping
  std::string json;
  std::string profile;  ///< run one untimed sweep of this kind per scene
};

/// Raw steps/s of the scene's control sequence with `iterations` QuickStep iterations: the
/// best of `repetitions` runs of at least `minSeconds` each.
double rawRateWithIterations(Problem problem, const std::vector<Segment>& segments, int iterations,
                             const Options& options) {
  problem.physics.solverIterations = iterations;
  PlanningContext context(problem, 0, PropagationSettings{});
  rawSweep(context, segments);  // warm-up
  Rate best;
  for (int rep = 0; rep < options.repetitions; ++rep) {
    Work work;
    while (work.seconds < options.minSeconds) work += rawSweep(context, segments);
    best.keepBest(work);
  }
  return best.stepsPerSecond;
}

/// The two contexts of a scene: the problem's propagation step, and one physics step.
struct SceneContexts {
  Problem problem;
  std::unique_ptr<PlanningContext> propagate;
  std::unique_ptr<PlanningContext> propagate1;
};

SceneContexts makeContexts(const Problem& problem, const Options& options) {
  SceneContexts scene{problem, nullptr, nullptr};
  if (options.maxContacts) scene.problem.physics.maxContacts = *options.maxContacts;
  PropagationSettings settings;  // what the planners use: the problem's PropagationStepSize
  for (const auto& p : scene.problem.planner.parameters)
    if (p.name == "PropagationStepSize") settings.propagationStepSize = std::stod(p.value);
  scene.propagate = std::make_unique<PlanningContext>(scene.problem, 0, settings);
  settings.propagationStepSize = scene.problem.physics.stepSize;
  scene.propagate1 = std::make_unique<PlanningContext>(scene.problem, 0, settings);
  const Violation start = scene.propagate->startViolation();
  if (start != Violation::None)
    throw std::runtime_error("the start state of " + scene.problem.name +
                             " is invalid: " + kautham::physics::toString(start));
  return scene;
}

/// --profile: one untimed sweep of one kind, for valgrind --tool=callgrind.
void profileRun(const Problem& base, int cans, const Options& options) {
  SceneContexts scene = makeContexts(makeScene(base, cans), options);
  const std::vector<Segment> segments = sweep();
  std::vector<double> finalState;
  Work work;
  if (options.profile == "raw") {
    work = rawSweep(*scene.propagate, segments, &finalState);
  } else {
    ChainedRunner runner(options.profile == "propagate" ? *scene.propagate : *scene.propagate1);
    work = runner.run(segments, &finalState);
  }
  std::printf("%2d cans, one %s sweep: %llu physics steps, %llu calls, %d cans moved > 5 mm\n",
              cans, options.profile.c_str(), work.steps, work.calls,
              movedCans(*scene.propagate, finalState));
}

/// Measures one scene under the fixed control sequence `segments` (the pusher's sweep, or
/// armMotion() when empty).
SceneResult measure(const Problem& problem, const std::string& name, std::vector<Segment> segments,
                    const Options& options) {
  SceneContexts scene = makeContexts(problem, options);
  ChainedRunner propagate(*scene.propagate);
  ChainedRunner propagate1(*scene.propagate1);
  if (segments.empty()) segments = armMotion(scene.propagate->world());
  for (const Segment& s : segments)
    if (s.steps % propagate.stepsPerCall() != 0)
      throw std::runtime_error("a sweep segment is not a whole number of propagation steps");

  SceneResult result;
  result.name = name;
  result.objects = static_cast<int>(problem.objects.size());
  result.stepsPerCall = propagate.stepsPerCall();
  // Warm-up and sanity checks: the pusher must move cans, and how many states are invalid.
  std::vector<double> rawFinal, chainedFinal;
  std::vector<CallInput> inputs;
  const Work rawOnce = rawSweep(*scene.propagate, segments, &rawFinal);
  const Work chainedOnce = propagate.run(segments, &chainedFinal, &inputs);
  result.movedRaw = movedCans(*scene.propagate, rawFinal);
  result.movedChained = movedCans(*scene.propagate, chainedFinal);
  result.invalidPerSweep = chainedOnce.invalid;
  result.callsPerSweep = chainedOnce.calls;
  result.sweepsPerRepetition =
      static_cast<unsigned>(std::max(1.0, std::ceil(options.minSeconds / rawOnce.seconds)));

  // Each repetition interleaves the three kinds sweep by sweep, so that a busy moment of the
  // machine slows all of them; the fastest repetition of each kind counts.
  for (int rep = 0; rep < options.repetitions; ++rep) {
    Work raw, chained, chained1;
    for (unsigned i = 0; i < result.sweepsPerRepetition; ++i) {
      raw += rawSweep(*scene.propagate, segments);
      chained += propagate.run(segments);
      chained1 += propagate1.run(segments);
    }
    result.raw.keepBest(raw);
    result.propagate.keepBest(chained);
    result.propagate1.keepBest(chained1);
  }
  result.overhead = measureCallOverhead(*scene.propagate, segments, inputs, 0.2);
  return result;
}

SceneResult measureCans(const Problem& base, int cans, const Options& options) {
  return measure(makeScene(base, cans), std::to_string(cans) + " cans", sweep(), options);
}

/// The arm problems that exist: the two test problems, and problems/kuka_cans_*.xml.
std::vector<std::filesystem::path> armProblems() {
  const std::filesystem::path source(KAUTHAM_SOURCE_DIR);
  std::vector<std::filesystem::path> files = {source / "tests/data/kuka_table.xml",
                                              source / "tests/data/yumi_table.xml"};
  std::vector<std::filesystem::path> cans;
  for (const auto& entry : std::filesystem::directory_iterator(source / "problems")) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("kuka_cans_", 0) == 0 && entry.path().extension() == ".xml")
      cans.push_back(entry.path());
  }
  std::sort(cans.begin(), cans.end());
  files.insert(files.end(), cans.begin(), cans.end());
  return files;
}

SceneResult measureArm(const std::filesystem::path& file, const Options& options) {
  const Problem problem = kautham::core::loadProblem(file);
  SceneResult result = measure(problem, file.filename().string(), {}, options);
  const std::vector<Segment> segments =
      armMotion(makeContexts(problem, options).propagate->world());
  for (int iterations : options.armIterations)
    result.rawByIterations.emplace_back(
        iterations, rawRateWithIterations(problem, segments, iterations, options));
  return result;
}

// ---------------------------------------------------------------------------------------------
// Output

std::string cpuModel() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line))
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(' ', colon + 1));
    }
  return "unknown";
}

void printTable(const std::vector<SceneResult>& results) {
  if (results.empty()) return;
  const unsigned k = results.front().stepsPerCall;
  std::printf(
      "\n(a) raw World::step() loop; (b) propagate (%u steps) + check per call, chained;\n"
      "(c) ratio = time per physics step in (b) / in (a); (d) the same at 1 step per call\n",
      k);
  std::printf("\n%-16s %12s %12s %12s %9s %12s %9s\n", "scene", "(a) steps/s", "(b) calls/s",
              "(b) steps/s", "(c) ratio", "(d) calls/s", "(d) ratio");
  for (const SceneResult& r : results)
    std::printf("%-16s %12.0f %12.0f %12.0f %9.3f %12.0f %9.3f\n", r.name.c_str(),
                r.raw.stepsPerSecond, r.propagate.callsPerSecond, r.propagate.stepsPerSecond,
                r.ratio(), r.propagate1.callsPerSecond, r.ratio1());

  std::printf(
      "\nNon-physics work of a call, timed alone (us): write state + controls, read state,"
      "\ncheck; and the ratios it alone accounts for at %u and 1 step per call:\n",
      k);
  std::printf("%-16s %9s %9s %9s %9s %12s %12s\n", "scene", "total", "write", "read", "check",
              "ratio (b)", "ratio (d)");
  for (const SceneResult& r : results)
    std::printf("%-16s %9.2f %9.2f %9.2f %9.2f %12.4f %12.4f\n", r.name.c_str(),
                1e6 * r.overhead.total(), 1e6 * r.overhead.write, 1e6 * r.overhead.read,
                1e6 * r.overhead.check, r.overheadRatio(r.stepsPerCall), r.overheadRatio(1));

  bool header = false;
  for (const SceneResult& r : results) {
    if (r.rawByIterations.empty()) continue;
    if (!header) std::printf("\nArm scenes, raw steps/s by QuickStep iterations:\n");
    header = true;
    std::printf("%-16s", r.name.c_str());
    for (const auto& [iterations, rate] : r.rawByIterations)
      std::printf("  %4d: %8.0f (x%.2f)", iterations, rate,
                  r.rawByIterations.front().second / rate);
    std::printf("\n");
  }
}

void writeJson(const std::string& file, const std::vector<SceneResult>& results,
               const Problem& base, const Options& options) {
  std::ofstream out(file);
  if (!out) throw std::runtime_error("cannot write " + file);
  out << "{\n  \"cpu\": \"" << cpuModel() << "\",\n"
      << "  \"ode\": \"" << kautham::physics::OdeLibrary::version() << "\",\n"
      << "  \"physics_step\": " << base.physics.stepSize << ",\n"
      << "  \"solver_iterations\": " << base.physics.solverIterations << ",\n"
      << "  \"max_contacts\": " << options.maxContacts.value_or(base.physics.maxContacts) << ",\n"
      << "  \"sweep_steps\": " << totalSteps(sweep()) << ",\n"
      << "  \"min_seconds_per_repetition\": " << options.minSeconds << ",\n"
      << "  \"repetitions\": " << options.repetitions << ",\n"
      << "  \"scenes\": [\n";
  for (std::size_t i = 0; i < results.size(); ++i) {
    const SceneResult& r = results[i];
    out << "    {\"scene\": \"" << r.name << "\", \"objects\": " << r.objects
        << ", \"raw_steps_per_s\": " << r.raw.stepsPerSecond
        << ", \"steps_per_call\": " << r.stepsPerCall
        << ", \"propagate_check_calls_per_s\": " << r.propagate.callsPerSecond
        << ", \"propagate_check_steps_per_s\": " << r.propagate.stepsPerSecond
        << ", \"ratio\": " << r.ratio()
        << ", \"one_step_calls_per_s\": " << r.propagate1.callsPerSecond
        << ", \"ratio_one_step_per_call\": " << r.ratio1()
        << ", \"overhead_us_per_call\": " << 1e6 * r.overhead.total()
        << ", \"overhead_write_us\": " << 1e6 * r.overhead.write
        << ", \"overhead_read_us\": " << 1e6 * r.overhead.read
        << ", \"overhead_check_us\": " << 1e6 * r.overhead.check
        << ", \"cans_moved_raw\": " << r.movedRaw << ", \"cans_moved_chained\": " << r.movedChained
        << ", \"invalid_states_per_sweep\": " << r.invalidPerSweep
        << ", \"calls_per_sweep\": " << r.callsPerSweep
        << ", \"sweeps_per_repetition\": " << r.sweepsPerRepetition;
    for (const auto& [iterations, rate] : r.rawByIterations)
      out << ", \"raw_steps_per_s_" << iterations << "_iterations\": " << rate;
    out << "}" << (i + 1 < results.size() ? ",\n" : "\n");
  }
  out << "  ]\n}\n";
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  CLI::App app{
      "Physics throughput on problems/pusher_cans_5.xml with N cans, a pusher sweeping the "
      "table with fixed controls, and on the arm problems (each joint turning in turn): (a) raw "
      "ODE steps per second, (b) PhysicsPropagator::"
      "propagate + WorldValidityChecker::check calls chained as a planner does, (c) the ratio "
      "of their times per physics step (the project aims at <= 1.15), (d) that ratio with one "
      "physics step per call. See docs/performance.md."};
  app.add_option("--objects", options.objects, "Numbers of movable cans, one scene each (<= 52)")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--min-time", options.minSeconds,
                 "Seconds of raw stepping in each repetition, at least (whole sweeps)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--repetitions", options.repetitions, "Repetitions; the fastest one counts")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--max-contacts", options.maxContacts,
                 "Override the problem's contacts per pair (8), for comparisons only")
      ->check(CLI::Range(1, 64));
  app.add_flag("!--no-arms", options.arms, "Skip the arm problems (KUKA, YuMi)");
  app.add_option("--arm-iterations", options.armIterations,
                 "QuickStep iterations at which the arm scenes' raw stepping is also timed")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--json", options.json, "Also write the results to this JSON file");
  app.add_option("--profile", options.profile,
                 "Run one untimed sweep of one kind per scene and exit (for valgrind)")
      ->check(CLI::IsMember({"raw", "propagate", "propagate1"}));
  CLI11_PARSE(app, argc, argv);

  try {
    const Problem base = kautham::core::loadProblem(std::filesystem::path(KAUTHAM_SOURCE_DIR) /
                                                    "problems" / "pusher_cans_5.xml");
    if (!options.profile.empty()) {
      for (int cans : options.objects) profileRun(base, cans, options);
      return 0;
    }
    std::printf("CPU: %s; ODE %s, QuickStep %d iterations, step %g s, %d contacts per pair\n",
                cpuModel().c_str(), kautham::physics::OdeLibrary::version(),
                base.physics.solverIterations, base.physics.stepSize,
                options.maxContacts.value_or(base.physics.maxContacts));
    std::printf("sweep: %u physics steps; each repetition >= %.2f s of raw stepping; best of %d\n",
                totalSteps(sweep()), options.minSeconds, options.repetitions);

    std::vector<SceneResult> results;
    const auto report = [](const SceneResult& r) {
      std::printf(
          "%s: %u sweep(s) per repetition; objects moved > 5 mm by a sweep: %d (a), %d (b); "
          "invalid states in a sweep of (b): %llu of %llu\n",
          r.name.c_str(), r.sweepsPerRepetition, r.movedRaw, r.movedChained, r.invalidPerSweep,
          r.callsPerSweep);
      std::fflush(stdout);
    };
    for (int cans : options.objects) report(results.emplace_back(measureCans(base, cans, options)));
    if (options.arms)
      for (const auto& file : armProblems())
        report(results.emplace_back(measureArm(file, options)));
    printTable(results);
    if (!options.json.empty()) writeJson(options.json, results, base, options);
  } catch (const std::exception& e) {
    std::cerr << "physics_throughput: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

// Physics throughput: how fast ODE steps our scenes, and how much of that speed the planner's
// inner loop (PhysicsPropagator::propagate + WorldValidityChecker::check, chained from state to
// state) keeps. Scenes are pusher_cans_5.xml with 5, 20 and 40 cans; the pusher sweeps the table
// with a fixed control sequence so that it pushes cans. See docs/performance.md.

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
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
// 6 rows 10 cm apart from y = -0.16 to 0.34 (the back row 2.7 cm inside the table's edge).
// Columns are wider apart than the 2 cm gap needs: with the gripper centred on a column, that
// column's can sits between the fingers (inner edges at +-6 cm) and the next columns' cans
// clear the fingers (outer edges at +-7 cm) by 7 mm, so a push moves one column straight.
constexpr int kColumns = 9;
constexpr int kRows = 6;
constexpr double kColumnPitch = 0.11;
constexpr double kRowPitch = 0.10;
constexpr double kFirstRowY = -0.16;

struct Slot {
  double x = 0.0;
  double y = 0.0;
};

/// Can positions on a grid with 2 cm gaps, off the glass and off the pusher, nearest first to
/// the point between the pusher and the glass (so every scene is the smaller one plus a ring).
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
  const auto key = [](const Slot& s) {
    return std::hypot(s.x, s.y - -0.1);
  };
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
  std::vector<double> velocities;
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

unsigned totalSteps(const std::vector<Segment>& segments) {
  unsigned steps = 0;
  for (const Segment& s : segments) steps += s.steps;
  return steps;
}

// ---------------------------------------------------------------------------------------------
// Runs

double seconds(Clock::time_point from, Clock::time_point to) {
  return std::chrono::duration<double>(to - from).count();
}
double cpuNow() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

/// What one sweep did, for the sanity checks.
struct SweepOutcome {
  double seconds = 0.0;
  double cpu = 0.0;
  unsigned long long steps = 0;  ///< physics steps
  unsigned long long calls = 0;  ///< propagate + check calls (0 for raw stepping)
  unsigned long long invalid = 0;
  std::vector<double> finalState;
};

/// (a) World::step() in a loop from the start state, the controls set at each segment.
SweepOutcome rawSweep(PlanningContext& context, const std::vector<Segment>& segments,
                      bool keepFinalState) {
  World& world = context.world();
  world.writeState(context.startState().data());
  world.resetSolverSeed();
  world.takeEvents();
  SweepOutcome outcome;
  const double c0 = cpuNow();
  const Clock::time_point start = Clock::now();
  for (const Segment& s : segments) {
    world.setJointVelocities(s.velocities.data());
    for (unsigned i = 0; i < s.steps; ++i) world.step();
  }
  outcome.seconds = seconds(start, Clock::now());
  outcome.cpu = cpuNow() - c0;
  outcome.steps = totalSteps(segments);
  if (keepFinalState) {
    outcome.finalState.resize(context.layout().stateSize());
    world.readState(outcome.finalState.data());
  }
  return outcome;
}

/// (b) and (d): the planner's inner loop, propagate one propagation step then check the
/// result, each call starting from the previous result. The chain carries on through invalid
/// states (a planner would stop there) so that every run does the same physical work.
class ChainedRunner {
 public:
  explicit ChainedRunner(PlanningContext& context)
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

  SweepOutcome run(const std::vector<Segment>& segments, bool keepFinalState) {
    const auto& propagator = context_.propagator();
    const auto& checker = context_.validityChecker();
    const double duration = si_->getPropagationStepSize();
    double* velocities = control_->as<ompl::control::RealVectorControlSpace::ControlType>()->values;
    const std::vector<double>& start = context_.startState();
    std::copy(start.begin(), start.end(), WorldStateSpace::values(from_));
    const unsigned long long stepsBefore = propagator.counters().physicsSteps;

    SweepOutcome outcome;
    const double c0 = cpuNow();
    const Clock::time_point begin = Clock::now();
    for (const Segment& s : segments) {
      std::copy(s.velocities.begin(), s.velocities.end(), velocities);
      const unsigned calls = s.steps / stepsPerCall_;
      for (unsigned i = 0; i < calls; ++i) {
        propagator.propagate(from_, control_, duration, to_);
        {
          Violation v = checker.check(WorldStateSpace::values(to_));
          if (v != Violation::None) {
            ++outcome.invalid;
            if (getenv("PT_DEBUG") && outcome.invalid < 4)
              std::fprintf(stderr, "call %llu: %s\n", outcome.calls + i,
                           kautham::physics::toString(v));
          }
        }
        std::swap(from_, to_);
      }
      outcome.calls += calls;
    }
    outcome.seconds = seconds(begin, Clock::now());
    outcome.cpu = cpuNow() - c0;
    outcome.steps = propagator.counters().physicsSteps - stepsBefore;
    if (keepFinalState) {
      const double* values = WorldStateSpace::values(from_);
      outcome.finalState.assign(values, values + start.size());
    }
    return outcome;
  }

 private:
  PlanningContext& context_;
  ompl::control::SpaceInformationPtr si_;
  ompl::base::State* from_;
  ompl::base::State* to_;
  ompl::control::Control* control_;
  unsigned stepsPerCall_;
};

/// Movable objects whose centre ended more than 5 mm from where it started.
int movedCans(const PlanningContext& context, const std::vector<double>& finalState) {
  const WorldLayout& layout = context.layout();
  int moved = 0;
  for (std::size_t b = 0; b < layout.bodies.size(); ++b)
    if (layout.bodies[b].role == BodyRole::Movable &&
        (WorldLayout::position(finalState.data(), b) -
         WorldLayout::position(context.startState().data(), b))
                .norm() > 0.005)
      ++moved;
  return moved;
}

/// Best (highest) rate over the repetitions of one kind of run.
struct Rate {
  double stepsPerSecond = 0.0;
  double callsPerSecond = 0.0;

  void keepBest(const SweepOutcome& total) {
    if (total.seconds <= 0.0) return;
    const double steps = static_cast<double>(total.steps) / total.seconds;
    if (steps > stepsPerSecond) {
      stepsPerSecond = steps;
      callsPerSecond = static_cast<double>(total.calls) / total.seconds;
    }
  }
};

SweepOutcome& operator+=(SweepOutcome& sum, const SweepOutcome& one) {
  sum.seconds += one.seconds;
  sum.cpu += one.cpu;
  sum.steps += one.steps;
  sum.calls += one.calls;
  sum.invalid += one.invalid;
  return sum;
}

struct SceneResult {
  int objects = 0;
  unsigned sweepsPerRepetition = 0;
  Rate raw;
  Rate coarse;  ///< (b): one propagation step of the problem per call
  Rate fine;    ///< (d): one physics step per call
  unsigned coarseStepsPerCall = 0;
  int movedRaw = 0;
  int movedChained = 0;
  unsigned long long invalidCoarse = 0;
  unsigned long long coarseCallsPerSweep = 0;

  double ratio() const { return raw.stepsPerSecond / coarse.stepsPerSecond; }
  double ratioFine() const { return raw.stepsPerSecond / fine.stepsPerSecond; }
  /// Microseconds a call costs beyond its physics steps.
  double overheadPerCall(const Rate& rate, unsigned stepsPerCall) const {
    return 1e6 * (1.0 / rate.callsPerSecond - stepsPerCall / raw.stepsPerSecond);
  }
};

struct Options {
  std::vector<int> objects{5, 20, 40};
  double minSeconds = 0.7;
  int repetitions = 3;
  std::string json;
};

SceneResult measure(const Problem& base, int cans, const Options& options) {
  const Problem scene = makeScene(base, cans);
  PropagationSettings coarseSettings;  // the problem's propagation step, 0.05 s by default
  for (const auto& p : scene.planner.parameters)
    if (p.name == "PropagationStepSize") coarseSettings.propagationStepSize = std::stod(p.value);
  PropagationSettings fineSettings = coarseSettings;
  fineSettings.propagationStepSize = scene.physics.stepSize;

  PlanningContext coarseContext(scene, 0, coarseSettings);
  PlanningContext fineContext(scene, 0, fineSettings);
  if (coarseContext.startViolation() != Violation::None)
    throw std::runtime_error(
        "the start state of the " + std::to_string(cans) +
        "-can scene is invalid: " + kautham::physics::toString(coarseContext.startViolation()));
  ChainedRunner coarse(coarseContext);
  ChainedRunner fine(fineContext);
  const std::vector<Segment> segments = sweep();
  for (const Segment& s : segments)
    if (s.steps % coarse.stepsPerCall() != 0)
      throw std::runtime_error("a sweep segment is not a whole number of propagation steps");

  SceneResult result;
  result.objects = cans;
  result.coarseStepsPerCall = coarse.stepsPerCall();
  if (const char* only = getenv("PT_ONLY")) {
    std::string k = only;
    SweepOutcome o = k == "raw" ? rawSweep(coarseContext, segments, true)
                     : k == "chained" ? coarse.run(segments, true) : fine.run(segments, true);
    std::fprintf(stderr, "%s: %llu steps moved %d\n", only, o.steps, movedCans(coarseContext, o.finalState));
    return result;
  }
  // Warm-up, sanity checks, and the number of sweeps that makes a repetition long enough.
  const SweepOutcome rawOnce = rawSweep(coarseContext, segments, true);
  const SweepOutcome coarseOnce = coarse.run(segments, true);
  fine.run(segments, false);
  result.movedRaw = movedCans(coarseContext, rawOnce.finalState);
  if (getenv("PT_DEBUG")) {
    const auto& L = coarseContext.layout();
    for (std::size_t b = 0; b < L.bodies.size(); ++b) {
      auto p0 = WorldLayout::position(coarseContext.startState().data(), b);
      auto p1 = WorldLayout::position(rawOnce.finalState.data(), b);
      auto p2 = WorldLayout::position(coarseOnce.finalState.data(), b);
      std::fprintf(stderr,
                   "%-16s start %.3f %.3f %.3f  raw %.3f %.3f %.3f  chained %.3f %.3f %.3f\n",
                   L.bodies[b].name.c_str(), p0.x(), p0.y(), p0.z(), p1.x(), p1.y(), p1.z(), p2.x(),
                   p2.y(), p2.z());
    }
  }
  result.movedChained = movedCans(coarseContext, coarseOnce.finalState);
  result.invalidCoarse = coarseOnce.invalid;
  result.coarseCallsPerSweep = coarseOnce.calls;
  result.sweepsPerRepetition =
      static_cast<unsigned>(std::max(1.0, std::ceil(options.minSeconds / rawOnce.seconds)));

  // Repetitions interleave the three kinds of run, so a slow phase of the machine hits all.
  for (int rep = 0; rep < options.repetitions; ++rep) {
    SweepOutcome raw, chained, single;
    for (unsigned i = 0; i < result.sweepsPerRepetition; ++i) {
      if (getenv("PT_SWAP")) {
        single += fine.run(segments, false);
        chained += coarse.run(segments, false);
        raw += rawSweep(coarseContext, segments, false);
      } else {
      raw += rawSweep(coarseContext, segments, false);
      chained += coarse.run(segments, false);
      single += fine.run(segments, false);
      }
    }
    if (getenv("PT_DEBUG"))
      std::fprintf(stderr, "rep %d: raw %.0f chained %.0f single %.0f  ratio %.3f %.3f\n", rep,
                   raw.steps / raw.seconds, chained.steps / chained.seconds,
                   single.steps / single.seconds,
                   (chained.seconds / chained.steps) / (raw.seconds / raw.steps),
                   (single.seconds / single.steps) / (raw.seconds / raw.steps));
    if (getenv("PT_DEBUG"))
      std::fprintf(stderr, "  cpu: raw %.0f chained %.0f single %.0f  ratio %.3f %.3f\n",
                   raw.steps / raw.cpu, chained.steps / chained.cpu,
                   single.steps / single.cpu,
                   (chained.cpu / chained.steps) / (raw.cpu / raw.steps),
                   (single.cpu / single.steps) / (raw.cpu / raw.steps));
    result.raw.keepBest(raw);
    result.coarse.keepBest(chained);
    result.fine.keepBest(single);
  }
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
  std::printf("\n%7s %13s %13s %13s %9s %13s %9s\n", "objects", "raw steps/s", "prop+chk/s",
              "steps/s", "ratio", "1-step call/s", "ratio@1");
  for (const SceneResult& r : results)
    std::printf("%7d %13.0f %13.0f %13.0f %9.3f %13.0f %9.3f\n", r.objects, r.raw.stepsPerSecond,
                r.coarse.callsPerSecond, r.coarse.stepsPerSecond, r.ratio(), r.fine.callsPerSecond,
                r.ratioFine());
  std::printf("\noverhead per call beyond its physics steps (microseconds):\n");
  for (const SceneResult& r : results)
    std::printf("%7d objects: %.2f us per %u-step call, %.2f us per 1-step call\n", r.objects,
                r.overheadPerCall(r.coarse, r.coarseStepsPerCall), r.coarseStepsPerCall,
                r.overheadPerCall(r.fine, 1));
}

void writeJson(const std::string& file, const std::vector<SceneResult>& results,
               const Problem& base, const Options& options) {
  std::ofstream out(file);
  if (!out) throw std::runtime_error("cannot write " + file);
  out << "{\n  \"cpu\": \"" << cpuModel() << "\",\n"
      << "  \"ode\": \"" << kautham::physics::OdeLibrary::version() << "\",\n"
      << "  \"physics_step\": " << base.physics.stepSize << ",\n"
      << "  \"solver_iterations\": " << base.physics.solverIterations << ",\n"
      << "  \"max_contacts\": " << base.physics.maxContacts << ",\n"
      << "  \"sweep_steps\": " << totalSteps(sweep()) << ",\n"
      << "  \"repetitions\": " << options.repetitions << ",\n"
      << "  \"scenes\": [\n";
  for (std::size_t i = 0; i < results.size(); ++i) {
    const SceneResult& r = results[i];
    out << "    {\"objects\": " << r.objects << ", \"raw_steps_per_s\": " << r.raw.stepsPerSecond
        << ", \"propagate_check_calls_per_s\": " << r.coarse.callsPerSecond
        << ", \"propagate_steps_per_s\": " << r.coarse.stepsPerSecond
        << ", \"steps_per_call\": " << r.coarseStepsPerCall << ", \"ratio\": " << r.ratio()
        << ", \"one_step_calls_per_s\": " << r.fine.callsPerSecond
        << ", \"ratio_one_step_per_call\": " << r.ratioFine()
        << ", \"cans_moved_raw\": " << r.movedRaw << ", \"cans_moved_chained\": " << r.movedChained
        << ", \"invalid_states_per_sweep\": " << r.invalidCoarse
        << ", \"calls_per_sweep\": " << r.coarseCallsPerSweep
        << ", \"sweeps_per_repetition\": " << r.sweepsPerRepetition << "}"
        << (i + 1 < results.size() ? ",\n" : "\n");
  }
  out << "  ]\n}\n";
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  CLI::App app{
      "Physics throughput: raw ODE steps per second against PhysicsPropagator::propagate + "
      "WorldValidityChecker::check chained as a planner does, on problems/pusher_cans_5.xml "
      "with N cans and a pusher sweeping the table. The ratio is the time per physics step "
      "through the propagator over the time per raw step (the project aims at <= 1.15)."};
  app.add_option("--objects", options.objects, "Numbers of movable cans, one scene each")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--min-time", options.minSeconds,
                 "Seconds each repetition runs at least (whole sweeps)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--repetitions", options.repetitions, "Repetitions, the best one counts")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--json", options.json, "Also write the results to this JSON file");
  CLI11_PARSE(app, argc, argv);

  try {
    const Problem base = kautham::core::loadProblem(std::filesystem::path(KAUTHAM_SOURCE_DIR) /
                                                    "problems" / "pusher_cans_5.xml");
    std::printf("CPU: %s; ODE %s, QuickStep %d iterations, step %g s, %d contacts per pair\n",
                cpuModel().c_str(), kautham::physics::OdeLibrary::version(),
                base.physics.solverIterations, base.physics.stepSize, base.physics.maxContacts);
    std::printf("sweep: %u physics steps; each repetition >= %.2f s; best of %d\n",
                totalSteps(sweep()), options.minSeconds, options.repetitions);

    std::vector<SceneResult> results;
    for (int cans : options.objects) {
      results.push_back(measure(base, cans, options));
      const SceneResult& r = results.back();
      std::printf(
          "%2d cans: %u sweeps per repetition; cans moved > 5 mm by one sweep: %d (raw "
          "stepping), %d (chained); invalid states in a chained sweep: %llu of %llu\n",
          cans, r.sweepsPerRepetition, r.movedRaw, r.movedChained, r.invalidCoarse,
          r.coarseCallsPerSweep);
      std::fflush(stdout);
    }
    printTable(results);
    if (!options.json.empty()) writeJson(options.json, results, base, options);
  } catch (const std::exception& e) {
    std::cerr << "physics_throughput: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

// Sampling the uncertain parts of a run (UncertaintySampler), the world's contact parameters,
// and open-loop execution under uncertainty (physics::execute), on the real ODE world.

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "TestPaths.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/physics/Execution.h"
#include "kautham/physics/PlanningContext.h"
#include "kautham/physics/UncertaintySampler.h"

namespace kautham::physics {
namespace {

core::Problem cans5() { return core::loadProblem(test::repoFile("problems/pusher_cans_5.xml")); }

std::size_t bodyNamed(const WorldLayout& layout, const std::string& name) {
  for (std::size_t b = 0; b < layout.bodies.size(); ++b)
    if (layout.bodies[b].name == name) return b;
  throw std::runtime_error("no body " + name);
}

core::ObjectInstance& object(core::Problem& problem, const char* name) {
  return problem.objects.at(static_cast<std::size_t>(*problem.findObject(name)));
}

struct Moments {
  double mean = 0.0;
  double sd = 0.0;
};

Moments moments(const std::vector<double>& values) {
  double sum = 0.0, squares = 0.0;
  for (double v : values) sum += v;
  const double mean = sum / values.size();
  for (double v : values) squares += (v - mean) * (v - mean);
  return {mean, std::sqrt(squares / (values.size() - 1))};
}

double tilt(const double* state, std::size_t body) {
  const Eigen::Vector3d up = WorldLayout::orientation(state, body) * Eigen::Vector3d::UnitZ();
  return std::acos(std::clamp(up.z(), -1.0, 1.0));
}

TEST(UncertaintySampler, InitialPosesHaveTheGivenSpreadAndOnlyUncertainObjectsMove) {
  core::Problem problem = cans5();
  const PlanningContext context(problem, 0, PropagationSettings{});
  object(problem, "can1").uncertainty = {0.02, 0.01, 0.2};
  const UncertaintySampler sampler(problem, context.layout());
  const WorldLayout& layout = context.layout();
  const std::size_t can1 = bodyNamed(layout, "can1");
  EXPECT_DOUBLE_EQ(sampler.initialUncertainty(can1).x, 0.02);
  EXPECT_TRUE(sampler.initialUncertainty(bodyNamed(layout, "can2")).isZero());
  EXPECT_TRUE(sampler.hasUncertainty());

  const std::vector<double>& start = context.startState();
  const Eigen::Vector3d home = planarPose(start.data(), can1);
  std::vector<double> dx, dy, dyaw;
  std::mt19937_64 rng(5);
  constexpr int kDraws = 20000;
  for (int i = 0; i < kDraws; ++i) {
    std::vector<double> state = start;
    sampler.sampleInitialPoses(state.data(), rng);
    const Eigen::Vector3d pose = planarPose(state.data(), can1);
    dx.push_back(pose.x() - home.x());
    dy.push_back(pose.y() - home.y());
    dyaw.push_back(std::remainder(pose.z() - home.z(), 2.0 * M_PI));
    ASSERT_DOUBLE_EQ(WorldLayout::position(state.data(), can1).z(),
                     WorldLayout::position(start.data(), can1).z());
    ASSERT_NEAR(tilt(state.data(), can1), tilt(start.data(), can1), 1e-9);
    // Every other number of the state (other bodies, joints, velocities) is untouched.
    for (std::size_t k = 0; k < state.size(); ++k) {
      if (k / WorldLayout::kBodyStateSize != can1 || k >= layout.jointPositionIndex()) {
        ASSERT_EQ(state[k], start[k]) << k;
      }
    }
  }
  // Standard errors: mean sd/141, standard deviation sd/200; bounds at about 5 of them.
  const Moments mx = moments(dx), my = moments(dy), myaw = moments(dyaw);
  EXPECT_NEAR(mx.mean, 0.0, 0.02 / 141 * 5);
  EXPECT_NEAR(my.mean, 0.0, 0.01 / 141 * 5);
  EXPECT_NEAR(myaw.mean, 0.0, 0.2 / 141 * 5);
  EXPECT_NEAR(mx.sd, 0.02, 0.02 * 0.025);
  EXPECT_NEAR(my.sd, 0.01, 0.01 * 0.025);
  EXPECT_NEAR(myaw.sd, 0.2, 0.2 * 0.025);
}

TEST(UncertaintySampler, ZeroStandardDeviationsChangeNothing) {
  const core::Problem problem = cans5();
  const PlanningContext context(problem, 0, PropagationSettings{});
  const UncertaintySampler sampler(problem, context.layout());
  EXPECT_FALSE(sampler.hasUncertainty());
  std::mt19937_64 rng(1);
  std::vector<double> state = context.startState();
  sampler.sampleInitialPoses(state.data(), rng);
  EXPECT_EQ(state, context.startState());
  const ContactParameters contact = sampler.sampleContact(rng);
  EXPECT_EQ(contact.friction, problem.physics.friction);
  EXPECT_EQ(contact.erp, problem.physics.erp);
  EXPECT_EQ(contact.cfm, problem.physics.cfm);
  const double control[3] = {0.3, -1.0, 0.99};
  double noisy[3];
  sampler.perturbControl(control, noisy, 3, rng);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(noisy[i], control[i]);
}

TEST(UncertaintySampler, AnyStandardDeviationMakesItUncertain) {
  const core::Problem base = cans5();
  const PlanningContext context(base, 0, PropagationSettings{});
  for (int which = 0; which < 5; ++which) {
    core::Problem problem = base;
    if (which == 0) problem.uncertainty.friction = 0.1;
    if (which == 1) problem.uncertainty.erp = 0.1;
    if (which == 2) problem.uncertainty.cfm = 1e-6;
    if (which == 3) problem.uncertainty.control = 0.05;
    if (which == 4) object(problem, "glass").uncertainty.yaw = 0.1;
    EXPECT_TRUE(UncertaintySampler(problem, context.layout()).hasUncertainty()) << which;
  }
}

TEST(UncertaintySampler, YawTurnsAboutWorldZAndKeepsTheTilt) {
  const core::Problem problem = cans5();
  const PlanningContext context(problem, 0, PropagationSettings{});
  const std::size_t can = bodyNamed(context.layout(), "can2");
  std::vector<double> state = context.startState();
  const Eigen::Quaterniond tilted(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()) *
                                  Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()));
  double* values = state.data() + can * WorldLayout::kBodyStateSize;
  values[3] = tilted.w(), values[4] = tilted.x(), values[5] = tilted.y(), values[6] = tilted.z();
  const double height = values[2];
  EXPECT_NEAR(planarPose(state.data(), can).z(), 0.5, 1e-12);

  setPlanarPose(state.data(), can, {0.1, -0.2, -1.0});
  EXPECT_TRUE(planarPose(state.data(), can).isApprox(Eigen::Vector3d(0.1, -0.2, -1.0), 1e-12));
  EXPECT_EQ(values[2], height);
  EXPECT_NEAR(tilt(state.data(), can), 0.3, 1e-12);
  const Eigen::Quaterniond expected(Eigen::AngleAxisd(-1.0, Eigen::Vector3d::UnitZ()) *
                                    Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()));
  EXPECT_NEAR(std::abs(WorldLayout::orientation(state.data(), can).dot(expected)), 1.0, 1e-12);
}

TEST(UncertaintySampler, ContactParametersAndControlsAreClippedToValidValues) {
  core::Problem problem = cans5();
  const PlanningContext context(problem, 0, PropagationSettings{});
  problem.uncertainty.friction = 1.0;
  problem.uncertainty.erp = 1.0;
  problem.uncertainty.cfm = 1e-4;
  problem.uncertainty.control = 0.5;
  const UncertaintySampler sampler(problem, context.layout());
  std::mt19937_64 rng(8);
  int frictionZero = 0, erpZero = 0, erpOne = 0, cfmZero = 0, controlOne = 0, controlMinusOne = 0;
  std::vector<double> frictions;
  for (int i = 0; i < 5000; ++i) {
    const ContactParameters c = sampler.sampleContact(rng);
    ASSERT_GE(c.friction, 0.0);
    ASSERT_GE(c.erp, 0.0);
    ASSERT_LE(c.erp, 1.0);
    ASSERT_GE(c.cfm, 0.0);
    frictionZero += c.friction == 0.0;
    erpZero += c.erp == 0.0;
    erpOne += c.erp == 1.0;
    cfmZero += c.cfm == 0.0;
    frictions.push_back(c.friction);
    const double control[2] = {0.9, -0.9};
    double noisy[2];
    sampler.perturbControl(control, noisy, 2, rng);
    for (double v : noisy) {
      ASSERT_GE(v, -1.0);
      ASSERT_LE(v, 1.0);
    }
    controlOne += noisy[0] == 1.0;
    controlMinusOne += noisy[1] == -1.0;
  }
  // N(0.5, 1) is below 0 with probability 0.31; N(0.2, 1) below 0 0.42, above 1 0.21;
  // N(1e-5, 1e-4) below 0 0.46; N(0.9, 0.5) above 1 0.42.
  EXPECT_NEAR(frictionZero / 5000.0, 0.31, 0.03);
  EXPECT_NEAR(erpZero / 5000.0, 0.42, 0.03);
  EXPECT_NEAR(erpOne / 5000.0, 0.21, 0.03);
  EXPECT_NEAR(cfmZero / 5000.0, 0.46, 0.03);
  EXPECT_NEAR(controlOne / 5000.0, 0.42, 0.03);
  EXPECT_NEAR(controlMinusOne / 5000.0, 0.42, 0.03);
}

// ----- the world's contact parameters -----

/// How far can4 slides in 0.3 s when it starts at 0.6 m/s along -x on the table.
double slide(World& world, const std::vector<double>& start, std::size_t can) {
  std::vector<double> state = start;
  state[can * WorldLayout::kBodyStateSize + WorldLayout::kLinearVelocity] = -0.6;
  world.writeState(state.data());
  const std::vector<double> still(world.actuators().size(), 0.0);
  world.setJointVelocities(still.data());
  world.resetSolverSeed();
  for (int i = 0; i < 30; ++i) world.step();
  world.readState(state.data());
  return WorldLayout::position(start.data(), can).x() -
         WorldLayout::position(state.data(), can).x();
}

TEST(WorldContactParameters, StartAtThePhysicsBlockAndChangeHowObjectsSlide) {
  const core::Problem problem = cans5();
  PlanningContext context(problem, 0, PropagationSettings{});
  World& world = context.world();
  EXPECT_EQ(world.contactParameters().friction, problem.physics.friction);
  EXPECT_EQ(world.contactParameters().erp, problem.physics.erp);
  EXPECT_EQ(world.contactParameters().cfm, problem.physics.cfm);

  const std::size_t can = bodyNamed(context.layout(), "can4");
  const double nominal = slide(world, context.startState(), can);
  world.setContactParameters({0.0, 0.2, 1e-5});
  const double frictionless = slide(world, context.startState(), can);
  world.setContactParameters({1.0, 0.2, 1e-5});
  const double sticky = slide(world, context.startState(), can);
  // Without friction the can keeps its speed (0.18 m in 0.3 s); mu = 1 stops it in 2 cm.
  EXPECT_NEAR(frictionless, 0.18, 0.01);
  EXPECT_LT(sticky, 0.03);
  EXPECT_GT(nominal, sticky);
  EXPECT_LT(nominal, frictionless);

  EXPECT_THROW(world.setContactParameters({-0.1, 0.2, 1e-5}), std::invalid_argument);
  EXPECT_THROW(world.setContactParameters({0.5, 1.5, 1e-5}), std::invalid_argument);
  EXPECT_THROW(world.setContactParameters({0.5, 0.2, -1.0}), std::invalid_argument);
  EXPECT_EQ(world.contactParameters().friction, 1.0);  // a rejected value changes nothing
}

// ----- execution under uncertainty -----

/// The pusher drives forward into the cans, then sideways: contacts all along.
std::vector<ControlStep> pushingControls() {
  return {{{0.0, 0.8, 0.0}, 30}, {{0.4, 0.3, 0.1}, 6}, {{-0.3, 0.5, -0.2}, 8}};
}

void expectSameAsReplay(const ExecutionResult& e, const ReplayResult& r) {
  EXPECT_EQ(e.finalState, r.finalState());
  EXPECT_EQ(e.firstViolation, r.firstViolation);
  EXPECT_EQ(e.finalGoalDistance, r.finalGoalDistance);
  EXPECT_EQ(e.reachedGoal, r.reachedGoal);
  EXPECT_DOUBLE_EQ(e.time, r.frames.back().time);
}

TEST(Execution, WithoutSamplingItIsExactlyTheReplayAndDrawsNothing) {
  PlanningContext context(cans5(), 0, PropagationSettings{});
  const ReplayResult replayed = replay(context, pushingControls());
  ASSERT_GT(replayed.frames.size(), 10u) << toString(replayed.firstViolation);
  // Something was pushed: contacts are part of what must repeat.
  ASSERT_FALSE(movedObjects(context.layout(), replayed).empty())
      << replayed.frames.size() << " " << toString(replayed.firstViolation);
  std::mt19937_64 rng(3), untouched(3);
  expectSameAsReplay(execute(context, pushingControls(), rng, false), replayed);
  EXPECT_EQ(rng(), untouched());
}

TEST(Execution, SamplingAProblemWithoutUncertaintyIsAlsoTheReplay) {
  PlanningContext context(cans5(), 0, PropagationSettings{});
  const ReplayResult replayed = replay(context, pushingControls());
  std::mt19937_64 rng(3);
  const ExecutionResult executed = execute(context, pushingControls(), rng, true);
  expectSameAsReplay(executed, replayed);
  EXPECT_EQ(executed.startState, context.startState());
}

core::Problem uncertainCans5() {
  core::Problem problem = cans5();
  for (core::ObjectInstance& o : problem.objects)
    if (o.role != core::ObjectRole::Fixed) o.uncertainty = {0.01, 0.01, 0.2};
  problem.uncertainty = {0.1, 0.05, 1e-6, 0.1, {}};
  return problem;
}

TEST(Execution, SameStreamSameRunAndTheContactParametersAreRestored) {
  PlanningContext context(uncertainCans5(), 0, PropagationSettings{});
  context.world().setContactParameters({0.7, 0.3, 2e-5});
  std::mt19937_64 a(42), b(42), c(43);
  const ExecutionResult first = execute(context, pushingControls(), a, true);
  const ExecutionResult second = execute(context, pushingControls(), b, true);
  const ExecutionResult other = execute(context, pushingControls(), c, true);
  EXPECT_EQ(first.startState, second.startState);
  EXPECT_EQ(first.finalState, second.finalState);
  EXPECT_EQ(first.firstViolation, second.firstViolation);
  EXPECT_NE(first.startState, other.startState);
  EXPECT_NE(first.contact.friction, other.contact.friction);
  EXPECT_NE(first.startState, context.startState());
  // The sampled contact parameters were used during the run, and are gone afterwards.
  EXPECT_NE(first.contact.friction, 0.7);
  EXPECT_EQ(context.world().contactParameters().friction, 0.7);
  EXPECT_EQ(context.world().contactParameters().erp, 0.3);
  EXPECT_EQ(context.world().contactParameters().cfm, 2e-5);
}

TEST(Execution, TheTargetAndTheGoalStartWhereTheTargetWasSampled) {
  core::Problem problem = cans5();
  object(problem, "glass").uncertainty = {0.02, 0.02, 0.0};  // far beyond targetTolerance
  PlanningContext context(problem, 0, PropagationSettings{});
  const std::size_t glass = bodyNamed(context.layout(), "glass");
  const std::vector<ControlStep> wait{{{0.0, 0.0, 0.0}, 4}};
  int shifted = 0;
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    std::mt19937_64 rng(seed);
    const ExecutionResult r = execute(context, wait, rng, true);
    const Eigen::Vector3d shift = WorldLayout::position(r.startState.data(), glass) -
                                  WorldLayout::position(context.startState().data(), glass);
    shifted += shift.norm() > 0.005;
    // Standing still is valid even though the glass is far from its measured pose...
    EXPECT_EQ(r.firstViolation, Violation::None) << toString(r.firstViolation);
    // ...and the goal region moved with it.
    const Eigen::Vector3d goal = context.goal().position() + shift;
    EXPECT_NEAR(r.finalGoalDistance,
                (context.layout().goalLinkPosition(r.finalState.data()) - goal).norm(), 1e-9);
  }
  EXPECT_GE(shifted, 15);
}

TEST(PlanningContextGoal, TheGoalForAStartFollowsItsTargetAndIsNullOtherwise) {
  PlanningContext context(cans5(), 0, PropagationSettings{});
  const std::size_t glass = bodyNamed(context.layout(), "glass");
  std::vector<double> start = context.startState();
  EXPECT_EQ(context.goalForStart(start.data()), nullptr);  // nothing moved
  setPlanarPose(start.data(), glass,
                planarPose(start.data(), glass) + Eigen::Vector3d(0.01, -0.02, 0.3));
  const std::unique_ptr<WorkspaceGoal> moved = context.goalForStart(start.data());
  ASSERT_NE(moved, nullptr);
  // The pre-grasp point turns and shifts with the glass: its offset from the glass is kept.
  const Eigen::Vector3d before =
      context.goal().position() - WorldLayout::position(context.startState().data(), glass);
  const Eigen::Vector3d after = moved->position() - WorldLayout::position(start.data(), glass);
  EXPECT_NEAR(after.norm(), before.norm(), 1e-9);
  EXPECT_GT((after - before).norm(), 0.01);  // turned by 0.3 rad
  EXPECT_NEAR(after.z(), before.z(), 1e-9);
  EXPECT_DOUBLE_EQ(moved->spec().tolerance, context.goal().spec().tolerance);
}

}  // namespace
}  // namespace kautham::physics

#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <ompl/control/spaces/RealVectorControlSpace.h>

#include "TestPaths.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/physics/PlanningContext.h"

namespace kautham::test {

/// A planning context on a real problem file, with helpers to drive the robot through the
/// real propagator and to edit states.
class ContextFixture {
 public:
  explicit ContextFixture(const std::string& problemFile)
      : ContextFixture(core::loadProblem(repoFile(problemFile))) {}
  /// On a problem edited in memory (another control set, another goal).
  explicit ContextFixture(core::Problem edited)
      : problem(std::move(edited)),
        context(problem, 0, physics::PropagationSettings{}),
        state(context.startState()) {}

  std::size_t body(const std::string& name) const {
    const auto& bodies = context.layout().bodies;
    for (std::size_t b = 0; b < bodies.size(); ++b)
      if (bodies[b].name == name) return b;
    throw std::runtime_error("no body named " + name);
  }

  /// Applies joint velocities (through the controls that ask for them) for `steps`
  /// propagation steps, one propagate call each, and returns the first violation met
  /// (stopping there), or Violation::None.
  physics::Violation drive(const std::vector<double>& velocities, unsigned steps) {
    return driveControls(context.propagator().mapping().controlsFor(velocities), steps);
  }

  /// As drive(), with the planner's normalized controls.
  physics::Violation driveControls(const std::vector<double>& controls, unsigned steps) {
    const auto& si = context.spaceInformation();
    ompl::base::State* from = si->allocState();
    ompl::base::State* to = si->allocState();
    ompl::control::Control* control = si->allocControl();
    std::copy(controls.begin(), controls.end(),
              control->as<ompl::control::RealVectorControlSpace::ControlType>()->values);
    physics::Violation violation = physics::Violation::None;
    for (unsigned i = 0; i < steps && violation == physics::Violation::None; ++i) {
      std::copy(state.begin(), state.end(), physics::WorldStateSpace::values(from));
      context.propagator().propagate(from, control, si->getPropagationStepSize(), to);
      const double* values = physics::WorldStateSpace::values(to);
      state.assign(values, values + state.size());
      violation = context.validityChecker().check(state.data());
    }
    si->freeControl(control);
    si->freeState(from);
    si->freeState(to);
    return violation;
  }

  double* bodyState(const std::string& name) {
    return state.data() + body(name) * physics::WorldLayout::kBodyStateSize;
  }

  core::Problem problem;
  physics::PlanningContext context;
  std::vector<double> state;
};

/// A 2 kg, 30 cm box: an obstacle for the small scenes tests write themselves.
inline const char* const kBoxUrdf = R"(<?xml version="1.0"?>
<robot name="box">
  <link name="box">
    <inertial><mass value="2"/><inertia ixx="0.02" iyy="0.02" izz="0.02" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.3 0.3 0.3"/></geometry></collision>
  </link>
</robot>
)";

/// A scene a test writes itself: `files` (name, text) into a temporary folder, the problem
/// `problemFile` among them loaded, the folder removed.
inline core::Problem loadWrittenProblem(
    const std::string& folderName, const std::vector<std::pair<std::string, std::string>>& files,
    const std::string& problemFile) {
  namespace fs = std::filesystem;
  // One folder per process: CTest runs tests in parallel processes, and two tests that
  // write the same scene must not remove each other's files.
  const fs::path folder =
      fs::temp_directory_path() / (folderName + "_" + std::to_string(::getpid()));
  fs::create_directories(folder);
  for (const auto& [name, text] : files) std::ofstream(folder / name) << text;
  core::Problem problem = core::loadProblem(folder / problemFile);
  fs::remove_all(folder);
  return problem;
}

}  // namespace kautham::test

// How far ODE's QuickStep is from a converged answer along a plan (docs/physics.md, "How many
// solver iterations"). The plan's controls are run nominally with N iterations; from every
// state of that run, one propagation step is taken twice, with N iterations and with the
// reference count, and the two ends are compared: the robot's bodies, the movable objects'
// bodies, and how far each object tilted. Only the iteration count differs between the two, so
// the gap is the solver's error over one step, where the arm pushes and where it moves free.
//
//   solver_convergence --problem problems/kuka_clutter_20.xml --plan plan.json
//                      --iterations 20,40,100 --over-relaxation 1.3,1.7 --reference 1000
//                      --json out.json

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

#include <ompl/control/spaces/RealVectorControlSpace.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "PlanControls.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/physics/PlanningContext.h"
#include "kautham/physics/WorldStateSpace.h"

namespace {

using kautham::core::Problem;
using kautham::physics::BodyRole;
using kautham::physics::PlanningContext;
using kautham::physics::WorldLayout;
using kautham::physics::WorldStateSpace;

using kautham::benchmarks::PlanControl;
using kautham::benchmarks::readControls;

/// One propagation step of `control` from `from` in `context`.
std::vector<double> step(PlanningContext& context, const std::vector<double>& from,
                         const std::vector<double>& control) {
  const auto& si = *context.spaceInformation();
  ompl::base::State* a = si.allocState();
  ompl::base::State* b = si.allocState();
  ompl::control::Control* u = si.allocControl();
  std::copy(from.begin(), from.end(), WorldStateSpace::values(a));
  std::copy(control.begin(), control.end(),
            u->as<ompl::control::RealVectorControlSpace::ControlType>()->values);
  context.propagator().propagate(a, u, si.getPropagationStepSize(), b);
  const double* end = WorldStateSpace::values(b);
  std::vector<double> out(end, end + context.layout().stateSize());
  si.freeState(a);
  si.freeState(b);
  si.freeControl(u);
  return out;
}

double tilt(const double* state, std::size_t body) {
  const Eigen::Vector3d up = WorldLayout::orientation(state, body) * Eigen::Vector3d::UnitZ();
  return std::acos(std::clamp(up.z(), -1.0, 1.0));
}

/// The largest gap between two states: over the robot's bodies and over the objects' bodies
/// (position, m), and over the objects' tilts (rad).
struct Gap {
  double robot = 0.0;
  double objects = 0.0;
  double tilt = 0.0;
};

Gap gapBetween(const WorldLayout& layout, const double* a, const double* b) {
  Gap gap;
  for (std::size_t body = 0; body < layout.bodies.size(); ++body) {
    const double d = (WorldLayout::position(a, body) - WorldLayout::position(b, body)).norm();
    if (layout.bodies[body].role == BodyRole::Robot) {
      gap.robot = std::max(gap.robot, d);
    } else {
      gap.objects = std::max(gap.objects, d);
      gap.tilt = std::max(gap.tilt, std::abs(tilt(a, body) - tilt(b, body)));
    }
  }
  return gap;
}

double quantile(std::vector<double> values, double q) {
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(q * static_cast<double>(values.size() - 1))];
}

double mean(const std::vector<double>& values) {
  double sum = 0.0;
  for (double v : values) sum += v;
  return sum / static_cast<double>(values.size());
}

struct Row {
  int iterations = 0;
  std::vector<double> robot, objects, tilts;
};

/// The reference is the same for every row (ODE's default over-relaxation, `reference`
/// iterations), so rows with other over-relaxation factors are measured against one answer.
Row measure(const Problem& base, const std::vector<PlanControl>& controls, int iterations,
            double overRelaxation, int reference) {
  Problem problem = base;
  problem.physics.solverIterations = iterations;
  problem.physics.overRelaxation = overRelaxation;
  PlanningContext context(problem, 0, {});
  problem.physics.solverIterations = reference;
  problem.physics.overRelaxation = kautham::core::PhysicsSettings{}.overRelaxation;
  PlanningContext converged(problem, 0, {});
  Row row;
  row.iterations = iterations;
  std::vector<double> state = context.startState();
  for (const PlanControl& control : controls) {
    for (unsigned s = 0; s < control.steps; ++s) {
      std::vector<double> next = step(context, state, control.values);
      const std::vector<double> exact = step(converged, state, control.values);
      const Gap gap = gapBetween(context.layout(), next.data(), exact.data());
      row.robot.push_back(gap.robot);
      row.objects.push_back(gap.objects);
      row.tilts.push_back(gap.tilt);
      state = std::move(next);
    }
  }
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "QuickStep's error along a plan: one propagation step with N iterations against "
      "one with the reference count, from every state of the plan's nominal run"};
  std::string problemFile, planFile, jsonFile;
  std::vector<int> iterations{10, 20, 40, 60, 100};
  std::vector<double> overRelaxations;
  int reference = 1000;
  app.add_option("--problem", problemFile, "problem file")->required();
  app.add_option("--plan", planFile, "plan file (from kautham plan -o)")->required();
  app.add_option("--iterations", iterations, "QuickStep iterations to measure")->delimiter(',');
  app.add_option("--over-relaxation", overRelaxations,
                 "QuickStep over-relaxation factors to measure (default: the file's)")
      ->delimiter(',');
  app.add_option("--reference", reference, "iterations taken as converged");
  app.add_option("--json", jsonFile, "write the numbers here too");
  CLI11_PARSE(app, argc, argv);
  try {
    const Problem problem = kautham::core::loadProblem(problemFile);
    const std::vector<PlanControl> controls = readControls(planFile);
    nlohmann::json out = {{"problem", problemFile}, {"plan", planFile}, {"reference", reference}};
    std::cout
        << "one propagation step's gap to " << reference
        << " iterations (robot and objects: largest body position gap, mm; tilt: mrad)\n"
        << "  W  iterations  robot mean  p95   max   objects mean  p95   max   tilt p95   max\n";
    if (overRelaxations.empty()) overRelaxations.push_back(problem.physics.overRelaxation);
    for (double w : overRelaxations)
      for (int n : iterations) {
        const Row row = measure(problem, controls, n, w, reference);
        std::cout << std::fixed << std::setprecision(2) << std::setw(4) << w << std::setw(11) << n
                  << std::setw(12) << 1e3 * mean(row.robot) << std::setw(6)
                  << 1e3 * quantile(row.robot, 0.95) << std::setw(7)
                  << 1e3 * quantile(row.robot, 1.0) << std::setw(14) << 1e3 * mean(row.objects)
                  << std::setw(6) << 1e3 * quantile(row.objects, 0.95) << std::setw(7)
                  << 1e3 * quantile(row.objects, 1.0) << std::setw(10)
                  << 1e3 * quantile(row.tilts, 0.95) << std::setw(7)
                  << 1e3 * quantile(row.tilts, 1.0) << "\n";
        out["rows"].push_back({{"iterations", n},
                               {"over_relaxation", w},
                               {"steps", row.robot.size()},
                               {"robot_mean_m", mean(row.robot)},
                               {"robot_p95_m", quantile(row.robot, 0.95)},
                               {"robot_max_m", quantile(row.robot, 1.0)},
                               {"objects_mean_m", mean(row.objects)},
                               {"objects_p95_m", quantile(row.objects, 0.95)},
                               {"objects_max_m", quantile(row.objects, 1.0)},
                               {"tilt_p95_rad", quantile(row.tilts, 0.95)},
                               {"tilt_max_rad", quantile(row.tilts, 1.0)}});
      }
    if (!jsonFile.empty()) std::ofstream(jsonFile) << out.dump(2) << "\n";
  } catch (const std::exception& e) {
    std::cerr << "solver_convergence: " << e.what() << "\n";
    return 2;
  }
  return 0;
}

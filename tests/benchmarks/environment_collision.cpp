// Collision cost of a sensed environment: how fast ODE steps problems/pusher_shelf.xml when
// its shelf is replaced by N static boxes scattered over the shelf's volume (the worst case
// for box merging: no two boxes touch), (a) as one fixed object, which the world puts in a
// collision space of its own, and (b) as N fixed objects of one box each, which all sit in the
// world's flat space. The pusher drives forward to the shelf and sweeps along it, so its
// gripper is inside the environment's bounding box for most of the run. See docs/physics.md.
//
//   build/tests/environment_collision [--boxes 0,100,500,2000] [--repeats 3]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "kautham/core/OctomapEnvironment.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/physics/World.h"

namespace {

using kautham::core::ObjectInstance;
using kautham::core::OctomapBoxes;
using kautham::core::Problem;
using kautham::physics::World;
using Clock = std::chrono::steady_clock;

/// `count` 2 cm voxels on a 4 cm lattice over the shelf's volume behind the table
/// (x in [-0.5, 0.5], y in [0.42, 0.72], z in [0, 1.6]): none touches another.
OctomapBoxes scatteredBoxes(int count) {
  std::vector<Eigen::Vector3i> cells;
  for (int i = 0; i < 25; ++i)
    for (int j = 0; j < 7; ++j)
      for (int k = 0; k < 40; ++k) cells.emplace_back(i, j, k);
  std::mt19937 random(1);
  std::shuffle(cells.begin(), cells.end(), random);
  OctomapBoxes boxes;
  boxes.resolution = 0.02;
  for (int n = 0; n < count && n < static_cast<int>(cells.size()); ++n) {
    const Eigen::Vector3d min(-0.5 + 0.04 * cells[n].x(), 0.42 + 0.04 * cells[n].y(),
                              0.04 * cells[n].z());
    boxes.boxes.emplace_back(min, min + Eigen::Vector3d::Constant(0.02));
  }
  boxes.leaves = boxes.boxes.size();
  return boxes;
}

Problem withEnvironment(const Problem& base, int count, bool oneObject) {
  Problem problem = base;
  problem.objects.erase(problem.objects.begin() + *problem.findObject("shelf"));
  const OctomapBoxes boxes = scatteredBoxes(count);
  if (oneObject) {
    if (count > 0)
      problem.objects.push_back(
          kautham::core::makeEnvironmentObject("shelf", "", boxes, {}, {problem.file, 0}));
    return problem;
  }
  for (std::size_t b = 0; b < boxes.boxes.size(); ++b) {
    OctomapBoxes one = boxes;
    one.boxes = {boxes.boxes[b]};
    problem.objects.push_back(kautham::core::makeEnvironmentObject("box" + std::to_string(b), "",
                                                                   one, {}, {problem.file, 0}));
  }
  return problem;
}

/// Physics steps per second over the sweep, the best of `repeats` runs.
double stepsPerSecond(const Problem& problem, int repeats) {
  World world(problem, problem.queries.front());
  std::vector<double> start(world.layout().stateSize());
  world.readState(start.data());
  struct Segment {
    double vx, vy;
    int steps;
  };
  // forward 0.6 m, then along the shelf and back, 2 mm per step
  const std::vector<Segment> sweep{{0, 0.2, 300}, {0.2, 0, 150}, {-0.2, 0, 300}, {0.2, 0, 150}};
  double best = 0.0;
  for (int r = 0; r < repeats; ++r) {
    world.writeState(start.data());
    world.resetSolverSeed();
    int steps = 0;
    const auto begin = Clock::now();
    for (const Segment& s : sweep) {
      const double velocities[3] = {s.vx, s.vy, 0.0};
      world.setJointVelocities(velocities);
      for (int i = 0; i < s.steps; ++i, ++steps) world.step();
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - begin).count();
    best = std::max(best, steps / seconds);
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("Physics steps per second with N static environment boxes");
  std::vector<int> counts{0, 10, 100, 500, 2000};
  int repeats = 3;
  app.add_option("--boxes", counts, "numbers of boxes")->delimiter(',');
  app.add_option("--repeats", repeats, "runs per measurement; the fastest counts");
  CLI11_PARSE(app, argc, argv);

  const Problem base =
      kautham::core::loadProblem(std::string(KAUTHAM_SOURCE_DIR) + "/problems/pusher_shelf.xml");
  std::printf("%8s  %22s  %22s  %6s\n", "boxes", "own space (steps/s)", "flat space (steps/s)",
              "ratio");
  for (int count : counts) {
    const double own = stepsPerSecond(withEnvironment(base, count, true), repeats);
    const double flat = stepsPerSecond(withEnvironment(base, count, false), repeats);
    std::printf("%8d  %22.0f  %22.0f  %6.2f\n", count, own, flat, own / flat);
  }
  return 0;
}

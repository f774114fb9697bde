// `kautham check PROBLEM`: load and validate a problem, and summarise it, without planning.

#include <map>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "Commands.h"
#include "KauthamPlanners.h"
#include "PackagePathOption.h"
#include "SideGraspClutter.h"
#include "StartCheck.h"
#include "kautham/core/ApproachCorridor.h"
#include "kautham/core/Log.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/physics/SelfOverlap.h"
#include "kautham/planners/geometric/GoalPoseOverlaps.h"

namespace kautham::apps {

namespace {

struct CheckOptions {
  std::string problem;
  std::vector<std::string> modelDirs;
  std::vector<std::string> packagePaths;
  std::optional<std::string> planner;
};

const char* jointTypeName(core::JointType type) {
  switch (type) {
    case core::JointType::Revolute:
      return "revolute";
    case core::JointType::Continuous:
      return "continuous";
    case core::JointType::Prismatic:
      return "prismatic";
    case core::JointType::Fixed:
      return "fixed";
  }
  return "?";
}

void printRobot(const core::RobotInstance& robot) {
  const std::vector<int> joints = robot.model.movableJoints();
  fmt::print("robot       {} ({}), {} degrees of freedom:\n", robot.name,
             robot.urdf.filename().string(), joints.size());
  for (int j : joints) {
    const core::Joint& joint = robot.model.joints[j];
    const bool prismatic = joint.type == core::JointType::Prismatic;
    fmt::print("              {:<12} {:<10} [{:g}, {:g}] {}, up to {:g} {}, effort {:g} {}\n",
               joint.name, jointTypeName(joint.type), joint.lower, joint.upper,
               prismatic ? "m" : "rad", joint.maxVelocity, prismatic ? "m/s" : "rad/s",
               joint.maxEffort, prismatic ? "N" : "N m");
  }
}

/// Robot links that move but have no mass (no <inertial>, nor one on a link fixed to them): the
/// physics gives their body a small default, which decides how hard they push. A <mass> written
/// as zero is named with its line: that is the line to fix.
void warnMasslessLinks(const core::RobotInstance& robot) {
  const core::KinematicModel& model = robot.model;
  std::vector<std::string> withoutInertial;
  for (int j : model.movableJoints()) {
    double mass = 0.0;
    const core::Link* zeroMass = nullptr;
    std::vector<int> pending{model.joints[j].childLink};
    while (!pending.empty()) {
      const core::Link& link = model.links[static_cast<std::size_t>(pending.back())];
      pending.pop_back();
      mass += link.inertial.mass;
      if (link.inertial.massLine > 0 && !zeroMass) zeroMass = &link;
      for (int c : link.childJoints)
        if (!model.joints[c].isMovable()) pending.push_back(model.joints[c].childLink);
    }
    if (mass > 0.0) continue;
    if (zeroMass)
      core::warning(fmt::format(
          "{}:{}: robot link '{}' has a zero <mass> (its body gets 0.1 kg, which sets how hard "
          "it pushes); give it its real, positive mass (kg)",
          robot.urdf.string(), zeroMass->inertial.massLine, zeroMass->name));
    else
      withoutInertial.push_back(
          model.links[static_cast<std::size_t>(model.joints[j].childLink)].name);
  }
  if (!withoutInertial.empty())
    core::warning(fmt::format(
        "{}: robot links without <inertial> (their bodies get 0.1 kg, which sets how hard they "
        "push): {}",
        robot.urdf.string(), fmt::join(withoutInertial, ", ")));
}

/// Deeper than this, two of the robot's own links overlap for real, not by a modelling sliver.
constexpr double kSelfOverlapDepth = 0.002;  // m

/// The robot's own links interpenetrating at a query's start. Planning has no self-collision
/// (the physics never collides a robot with itself), so it is a warning: the real robot could
/// not be there, and a plan may pass through itself the same way.
void warnSelfOverlaps(const core::Problem& problem, const core::Query& query) {
  for (const physics::LinkOverlap& o : physics::robotSelfOverlaps(
           problem.robot, problem.initialJointValues(query), kSelfOverlapDepth))
    core::warning(fmt::format(
        "{}: query '{}': robot links '{}' and '{}' interpenetrate at the start ({:.1f} mm); "
        "planning does not collide the robot with itself, so a plan may pass through itself "
        "too",
        query.where.str(), query.name, o.first, o.second, 1000.0 * o.depth));
}

/// Every mesh of the robot and the objects: how big it is, and how it collides.
void printMeshes(const core::Problem& problem) {
  std::vector<std::string> meshes;
  const auto describe = [&](const std::string& owner, const core::KinematicModel& model,
                            bool moves) {
    for (const core::Link& link : model.links)
      for (const core::CollisionShape& c : link.collisions)
        if (const auto* mesh = std::get_if<core::Mesh>(&c.shape))
          meshes.push_back(fmt::format("{} ({}: {} vertices, {} triangles; {})", owner,
                                       mesh->data->source.filename().string(),
                                       mesh->vertices().size(), mesh->triangles().size(),
                                       moves
                                           ? fmt::format("collides as its convex hull of {} faces",
                                                         mesh->hull().faces.size())
                                           : std::string("collides as its triangles")));
  };
  describe(problem.robot.name, problem.robot.model, true);
  for (const core::ObjectInstance& object : problem.objects)
    describe(object.name, object.model, object.role != core::ObjectRole::Fixed);
  if (!meshes.empty()) fmt::print("meshes      {}\n", fmt::join(meshes, "\n            "));
}

void printObjects(const core::Problem& problem) {
  std::map<core::ObjectRole, std::vector<std::string>> byRole;
  for (const core::ObjectInstance& object : problem.objects)
    byRole[object.role].push_back(object.name);
  for (auto role : {core::ObjectRole::Fixed, core::ObjectRole::Movable, core::ObjectRole::Target})
    fmt::print("{:<12}{}: {}\n", role == core::ObjectRole::Fixed ? "objects" : "",
               core::toString(role),
               byRole[role].empty() ? std::string("none")
                                    : fmt::format("{}", fmt::join(byRole[role], ", ")));
  printMeshes(problem);
  std::vector<std::string> uncertain;
  for (const core::ObjectInstance& o : problem.objects)
    if (o.uncertainty.x > 0 || o.uncertainty.y > 0 || o.uncertainty.yaw > 0)
      uncertain.push_back(fmt::format("{} (x {:g} m, y {:g} m, yaw {:g} rad)", o.name,
                                      o.uncertainty.x, o.uncertainty.y, o.uncertainty.yaw));
  for (const core::ObjectInstance& o : problem.objects)
    if (o.environment)
      fmt::print("environment {} ({}, {:g} m voxels): {} occupied leaves merged into {} boxes\n",
                 o.name, o.environment->octree.filename().string(), o.environment->resolution,
                 o.environment->leaves, o.environment->boxes);
  fmt::print("uncertainty {}\n",
             uncertain.empty() ? "none" : fmt::format("{}", fmt::join(uncertain, ", ")));
  const core::ContactUncertainty& u = problem.uncertainty;
  fmt::print("            sd of friction {:g}, ERP {:g}, CFM {:g}; control noise sd {:g}\n",
             u.friction, u.erp, u.cfm, u.control);
}

void printControls(const core::RobotInstance& robot) {
  const core::ControlSet& controls = robot.controls;
  const std::vector<int> movable = robot.model.movableJoints();
  std::vector<std::string> held;
  for (std::size_t i = 0; i < movable.size(); ++i)
    if (!controls.moves(i)) held.push_back(robot.model.joints[movable[i]].name);
  fmt::print(
      "controls    {} ({}): {}{}\n", controls.size(),
      controls.file.empty() ? std::string("one per joint") : controls.file.filename().string(),
      fmt::join(controls.names, ", "),
      held.empty() ? std::string() : fmt::format("; held: {}", fmt::join(held, ", ")));
}

void printSettings(const core::Problem& problem) {
  const core::PhysicsSettings& p = problem.physics;
  fmt::print(
      "physics     step {:g} s, {} solver iterations (over-relaxation {:g}), mu {:g}, ERP {:g}, "
      "CFM {:g}, {} contacts per pair\n",
      p.stepSize, p.solverIterations, p.overRelaxation, p.friction, p.erp, p.cfm, p.maxContacts);
  const core::InteractionConstraints& c = problem.interaction;
  const auto support = problem.supportObject();
  fmt::print(
      "constraints objects slower than {:g} m/s, tilted less than {:g} rad, on {}; target "
      "drifts less than {:g} m\n",
      c.maxObjectSpeed, c.maxTilt,
      support ? problem.objects[*support].name : std::string("any surface"), c.targetTolerance);
  const Eigen::AlignedBox3d& w = problem.workspace;
  fmt::print("workspace   x [{:g}, {:g}]  y [{:g}, {:g}]  z [{:g}, {:g}] m\n", w.min().x(),
             w.max().x(), w.min().y(), w.max().y(), w.min().z(), w.max().z());
  const core::KinodynamicLimits& k = problem.kinodynamics;
  fmt::print(
      "robot       joints within their limits (+{:g}), at most {:g}x their speed; links "
      "slower than {:g} m/s\n",
      k.jointLimitTolerance, k.jointSpeedFactor, k.maxLinkSpeed);
}

/// A side pre-grasp: the level axis, the free space and the objects blocking the approach.
void printSideGrasp(const core::Problem& problem, const core::GoalRegion& region) {
  if (region.levelAxis)
    fmt::print("            the goal link's axis ({:g}, {:g}, {:g}) level within {:g} rad\n",
               region.levelAxis->x(), region.levelAxis->y(), region.levelAxis->z(),
               region.approachTolerance);
  if (region.freeSpace) {
    const core::GoalRegion::FreeSpace& box = *region.freeSpace;
    fmt::print(
        "            free space: a {:g} x {:g} x {:g} m box at ({:g}, {:g}, {:g}) in the goal "
        "link's frame must hold no movable object\n",
        box.size.x(), box.size.y(), box.size.z(), box.center.x(), box.center.y(), box.center.z());
  }
  if (region.approachCorridor <= 0.0) return;
  const std::vector<std::string> blockers = core::approachBlockers(problem, region);
  int movable = 0;
  for (const core::ObjectInstance& object : problem.objects)
    movable += object.role == core::ObjectRole::Movable;
  const int needed = requiredBlockers(movable);
  const bool tooFew = static_cast<int>(blockers.size()) < needed;
  fmt::print(
      "blockers    {} of {} movable objects on the pre-grasp or in the {:g} m approach "
      "corridor{}{}{}\n",
      blockers.size(), movable, region.approachCorridor,
      needed > 0 ? fmt::format(" (the suite's rule asks for at least {}{})", needed,
                               tooFew ? ": too few" : "")
                 : "",
      blockers.empty() ? "" : ": ", fmt::join(blockers, ", "));
}

/// What the arm overlaps at the pre-grasp in the start scene (GoalPoseOverlaps): the objects
/// a plan must move.
void printGoalPoseOverlaps(physics::PlanningContext& context) {
  constexpr int kAttempts = 40;
  const planners::geometric::GoalPoseOverlaps overlaps =
      planners::geometric::goalPoseOverlaps(context, kAttempts);
  if (overlaps.poses == 0) {
    fmt::print(
        "at goal     no arm pose found by inverse kinematics in {} tries (within 5 mm and "
        "0.05 rad): the pre-grasp may be out of reach\n",
        kAttempts);
    return;
  }
  std::vector<std::string> touched;
  for (const auto& [name, count] : overlaps.objects)
    touched.push_back(fmt::format("{} {}", name, count));
  fmt::print(
      "at goal     {} arm poses by inverse kinematics, {} touch nothing in the start scene{}{}\n",
      overlaps.poses, overlaps.touchFree,
      touched.empty() ? "" : "; objects touched: ", fmt::join(touched, ", "));
}

/// Where the goal link is at the start (before the start is checked, so a person writing
/// <Init> sees where it put the robot even when the start is rejected).
void printGoalLinkStart(const core::Problem& problem, const core::Query& query) {
  const core::KinematicModel& model = problem.robot.model;
  const auto link = model.findLink(query.goal.link);
  if (!link) return;
  const auto poses =
      model.linkPoses(problem.robot.home.isometry(), problem.initialJointValues(query));
  const Eigen::Vector3d p = poses[static_cast<std::size_t>(*link)].translation();
  const Eigen::Vector3d z = poses[static_cast<std::size_t>(*link)].linear().col(2);
  fmt::print(
      "start       {}: {} at ({:.3f}, {:.3f}, {:.3f}), its +z along ({:.2f}, {:.2f}, {:.2f})\n",
      query.name, query.goal.link, p.x(), p.y(), p.z(), z.x(), z.y(), z.z());
}

int runCheck(const CheckOptions& options) {
  applyPackagePaths(options.packagePaths);
  std::vector<std::filesystem::path> modelDirs(options.modelDirs.begin(), options.modelDirs.end());
  const core::Problem problem = core::loadProblem(options.problem, modelDirs);
  const planners::PlanRequest request = planners::makeRequest(
      problem, plannerToUse(problem, options.planner, /*lenient=*/true), {}, 1);
  fmt::print("problem     {} ({})\n", problem.name, problem.file.string());
  printRobot(problem.robot);
  warnMasslessLinks(problem.robot);
  printControls(problem.robot);
  printObjects(problem);
  printSettings(problem);
  fmt::print("planner     {}\n", request.planner);
  for (std::size_t q = 0; q < problem.queries.size(); ++q) {
    printGoalLinkStart(problem, problem.queries[q]);
    warnSelfOverlaps(problem, problem.queries[q]);
    const auto context = makeCheckedContext(problem, q, request);  // throws if the start is bad
    const double* start = context->startState().data();
    const Eigen::Vector3d goal = context->goal().position();
    const core::GoalRegion& region = problem.queries[q].goal;
    if (region.isConfiguration()) {
      fmt::print(
          "query       {}: start valid; goal: a configuration, within {:g} (normalized joint "
          "units, {} at ({:.3g}, {:.3g}, {:.3g})), {:.3g} from the start\n",
          problem.queries[q].name, region.jointTolerance, region.link, goal.x(), goal.y(), goal.z(),
          context->goal().distance(start));
      continue;
    }
    const std::string approach = region.approach
                                     ? fmt::format(", +z within {:g} rad of the approach direction",
                                                   region.approachTolerance)
                                     : std::string();
    fmt::print(
        "query       {}: start valid; goal: {} within {:g} m of ({:g}, {:g}, {:g}){}, "
        "{:.1f} cm from the start\n",
        problem.queries[q].name, region.link, context->goal().getThreshold(), goal.x(), goal.y(),
        goal.z(), approach, 100.0 * context->goal().distance(start));
    printSideGrasp(problem, region);
    if (region.approach) printGoalPoseOverlaps(*context);
  }
  fmt::print("ok\n");
  return kExitSolved;
}

}  // namespace

void addCheckCommand(CLI::App& app, int& exitCode) {
  auto options = std::make_shared<CheckOptions>();
  CLI::App* command =
      app.add_subcommand("check", "Load and validate a problem file and summarise it");
  command->add_option("problem", options->problem, "problem file (XML)")->required();
  command->add_option("--model-dir", options->modelDirs, "extra folder to search for models")
      ->check(CLI::ExistingDirectory)
      ->allow_extra_args(false);
  command->add_option("--planner", options->planner,
                      "check with this planner instead of the file's (see `kautham planners`)");
  addPackagePathOption(*command, options->packagePaths);
  command->footer(
      "Exit codes: 0 the problem loads with a valid start, 2 bad input (the message names the "
      "file and line).\nExample: kautham check problems/kuka_clutter_20.xml");
  command->callback(
      [options, &exitCode] { exitCode = runReportingErrors([&] { return runCheck(*options); }); });
}

}  // namespace kautham::apps

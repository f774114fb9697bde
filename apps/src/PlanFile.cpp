#include "PlanFile.h"

#include <cmath>
#include <fstream>
#include <stdexcept>

#include <fmt/format.h>
#include <ompl/config.h>

#include "OutputFile.h"
#include "ShapeJson.h"
#include "VisualShapes.h"
#include "kautham/core/Version.h"
#include "kautham/physics/OdeLibrary.h"

namespace kautham::apps {

namespace {

using nlohmann::json;
using physics::WorldLayout;

json poseArray(const double* state, std::size_t body) {
  const double* s = state + body * WorldLayout::kBodyStateSize;
  return json::array({s[0], s[1], s[2], s[3], s[4], s[5], s[6]});
}

json jointNamesJson(const WorldLayout& layout) {
  json names = json::array();
  for (const physics::JointInfo& joint : layout.joints) names.push_back(joint.name);
  return names;
}

json trajectoryJson(const WorldLayout& layout, const physics::ReplayResult& replay) {
  json frames = json::array();
  for (const physics::ReplayFrame& frame : replay.frames) {
    json poses = json::array();
    for (std::size_t b = 0; b < layout.bodies.size(); ++b)
      poses.push_back(poseArray(frame.state.data(), b));
    // The robot's joint positions too: what a controller would follow (names in joint_names).
    const auto first = frame.state.begin() + static_cast<long>(layout.jointPositionIndex());
    const json joints = std::vector<double>(first, first + static_cast<long>(layout.joints.size()));
    frames.push_back(
        {{"t", frame.time}, {"poses", poses}, {"joints", joints}, {"touched", frame.touched}});
  }
  return frames;
}

json controlsJson(const planners::PlanOutcome& outcome, double stepSize,
                  const physics::WorldLayout& layout) {
  json controls = json::array();
  for (std::size_t i = 0; i < outcome.controls.size(); ++i) {
    const physics::ControlStep& c = outcome.controls[i];
    json control = {{"values", c.values}, {"steps", c.steps}, {"duration", c.steps * stepSize}};
    if (i < outcome.beliefs.size()) control["belief"] = outcome.beliefs[i];
    // The task planner's grasps and releases, at the start of the control.
    if (c.action != physics::GripperAction::None) control["gripper"] = toString(c.action);
    if (c.action == physics::GripperAction::Grasp) {
      control["body"] = c.object;
      control["object"] = layout.bodies.at(static_cast<std::size_t>(c.object)).name;
    }
    controls.push_back(control);
  }
  return controls;
}

json plannerPropertiesJson(const planners::PlanStatistics& statistics) {
  json properties = json::object();
  for (const auto& [name, value] : statistics.plannerProperties) properties[name] = value;
  return properties;
}

json failuresJson(const std::vector<planners::FailureCount>& failures) {
  json list = json::array();
  for (const planners::FailureCount& f : failures)
    list.push_back({{"reason", f.reason}, {"object", f.object}, {"count", f.count}});
  return list;
}

json bodiesJson(const WorldLayout& layout) {
  json bodies = json::array();
  for (const physics::BodyInfo& b : layout.bodies)
    bodies.push_back({{"name", b.name}, {"role", physics::toString(b.role)}});
  return bodies;
}

/// Every collision shape, so a viewer can draw the scene from the plan file alone.
json shapesJson(const WorldLayout& layout) {
  json shapes = json::array();
  for (const physics::ShapeInfo& s : layout.shapes) {
    json entry = shapeJson(s.shape);
    entry["owner"] = s.owner;
    entry["role"] = s.role;
    entry["body"] = s.body >= 0 ? json(s.body) : json(nullptr);
    entry["pose"] = poseJson(s.pose);
    shapes.push_back(entry);
  }
  return shapes;
}

/// Where the goal link went along the replay, frame by frame.
json linkPathJson(const WorldLayout& layout, const physics::ReplayResult& replay) {
  json path = json::array();
  for (const physics::ReplayFrame& frame : replay.frames) {
    const Eigen::Vector3d p = layout.goalLinkPosition(frame.state.data());
    path.push_back({p.x(), p.y(), p.z()});
  }
  return path;
}

/// The search tree, positions rounded to 0.1 mm: it is for pictures, and it can be large.
json treeJson(const planners::SearchTree& tree) {
  auto round = [](double v) { return std::round(v * 1e4) / 1e4; };
  json points = json::array();
  for (const Eigen::Vector3d& p : tree.endEffector)
    points.push_back({round(p.x()), round(p.y()), round(p.z())});
  json distances = json::array();
  for (double d : tree.goalDistance) distances.push_back(round(d));
  json result = {{"end_effector", points}, {"parent", tree.parent}, {"goal_distance", distances}};
  // Only a planner that judged every state has one belief per state.
  if (!tree.belief.empty() && tree.belief.size() == tree.parent.size()) {
    json beliefs = json::array();
    for (double b : tree.belief) beliefs.push_back(round(b));
    result["belief"] = beliefs;
  }
  return result;
}

}  // namespace

json planToJson(const physics::PlanningContext& context, const planners::PlanRequest& request,
                const planners::PlanOutcome& outcome, const physics::ReplayResult& replay) {
  const WorldLayout& layout = context.layout();
  const Eigen::Vector3d goal = context.goal().position();
  const double stepSize = context.spaceInformation()->getPropagationStepSize();
  json moved = json::array();
  for (const physics::ObjectDisplacement& m : physics::movedObjects(layout, replay))
    moved.push_back({{"name", m.name}, {"distance", m.distance}});

  return {
      {"format", "kautham-plan"},
      {"format_version", kPlanFormatVersion},
      {"versions",
       {{"kautham", core::version()},
        {"ompl",
         fmt::format("{}.{}.{}", OMPL_MAJOR_VERSION, OMPL_MINOR_VERSION, OMPL_PATCH_VERSION)},
        {"ode", physics::OdeLibrary::version()}}},
      {"problem",
       {{"name", context.problem().name},
        {"file", context.problem().file.string()},
        {"query", context.query().name}}},
      {"planner",
       {{"name", request.planner},
        {"parameters", request.parameters.values()},
        {"common", request.common.values()},
        // What OMPL's parameter set of the planner held: its benchmark logs record these.
        {"ompl_parameters", outcome.omplParameters}}},
      {"seed", request.seed},
      {"result",
       {{"solved", outcome.solved},
        {"approximate", outcome.approximate},
        {"goal_distance", outcome.goalDistance},
        {"replay",
         {{"reached_goal", replay.reachedGoal},
          {"violation", physics::toString(replay.firstViolation)},
          {"final_goal_distance", replay.finalGoalDistance},
          {"moved_objects", moved}}}}},
      {"statistics",
       {{"tree_states", outcome.statistics.treeStates},
        {"propagations", outcome.statistics.propagations},
        {"physics_steps", outcome.statistics.physicsSteps},
        {"planner", plannerPropertiesJson(outcome.statistics)},
        // Why the planner's particles failed, most frequent first (p-KPIECE; else empty).
        {"sampled_failures", failuresJson(outcome.sampledFailures)},
        // Why its candidate motions, run as planned, stopped at a broken rule, and of those
        // the goal steering's (p-KPIECE; else empty).
        {"candidate_failures", failuresJson(outcome.candidateFailures)},
        {"steered_failures", failuresJson(outcome.steeredFailures)}}},
      {"timing", {{"planning_time", outcome.statistics.planningTime}}},
      {"propagation_step_size", stepSize},
      {"controls", controlsJson(outcome, stepSize, layout)},
      {"bodies", bodiesJson(layout)},
      {"shapes", shapesJson(layout)},
      {"visuals", visualsJson(context.problem(), layout)},
      {"joint_names", jointNamesJson(layout)},
      {"frames", trajectoryJson(layout, replay)},
      {"goal",
       {{"position", {goal.x(), goal.y(), goal.z()}},
        {"tolerance", context.goal().getThreshold()},
        {"link", context.query().goal.link},
        {"link_path", linkPathJson(layout, replay)}}},
      {"tree", treeJson(outcome.tree)},
  };
}

void writeJsonFile(const std::filesystem::path& file, const nlohmann::json& json) {
  writeTextFile(file, json.dump(1) + '\n');
}

}  // namespace kautham::apps

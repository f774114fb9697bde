#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "kautham/physics/Replay.h"
#include "kautham/planners/Solve.h"

namespace kautham::apps {

/// Version of the plan file format; readers reject files of another version.
constexpr int kPlanFormatVersion = 2;  // 2: controls hold normalized "values" (were "velocities")

/// The plan file: the problem, planner, parameters and seed that produced it, statistics,
/// the controls with durations, every collision shape (static ones in the world, the others
/// in their body's frame), the robot's visual geometry (VisualShapes.h) and the pose of every
/// body along the replayed plan.
/// Everything but the "timing" object is identical for identical runs.
nlohmann::json planToJson(const physics::PlanningContext& context,
                          const planners::PlanRequest& request,
                          const planners::PlanOutcome& outcome,
                          const physics::ReplayResult& replay);

/// Writes JSON to a file, through a temporary file so a failed write never leaves half a plan.
void writeJsonFile(const std::filesystem::path& file, const nlohmann::json& json);

}  // namespace kautham::apps

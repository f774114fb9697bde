#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace kautham::apps {

/// An SVG picture of the search, seen from above: the table and obstacles, the objects at the
/// start, every tree state's end-effector position joined to its parent and coloured by how
/// close it came to the goal (by belief, when the planner recorded one), the goal region and
/// the plan's path. `plan` is a checked plan file (see checkPlanForView).
std::string treeToSvg(const nlohmann::json& plan);

}  // namespace kautham::apps

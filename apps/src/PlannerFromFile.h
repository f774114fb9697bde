#pragma once

// `kautham plan PROBLEM --planner-from FILE`: plan PROBLEM's scene and query with the planner,
// and its parameters, of another problem file's <Planner>. A Kautham benchmark file compares
// planners so: its first problem gives the scene, every problem its planner.

#include <filesystem>
#include <vector>

#include "kautham/core/Problem.h"

namespace kautham::apps {

/// `problem` with the <Planner> name and parameters of `file`, which is loaded (and checked) as
/// a whole problem; its scene, physics and queries are not used. Throws core::InputError.
core::Problem withPlannerOf(core::Problem problem, const std::filesystem::path& file,
                            const std::vector<std::filesystem::path>& modelDirs);

}  // namespace kautham::apps

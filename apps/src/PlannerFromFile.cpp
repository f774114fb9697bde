#include "PlannerFromFile.h"

#include "kautham/core/ProblemLoader.h"

namespace kautham::apps {

core::Problem withPlannerOf(core::Problem problem, const std::filesystem::path& file,
                            const std::vector<std::filesystem::path>& modelDirs) {
  // The whole file is loaded so that its <Planner> is read, and checked, exactly as `kautham
  // plan FILE` would: its parameters keep their lines for the messages about them.
  problem.planner = core::loadProblem(file, modelDirs).planner;
  return problem;
}

}  // namespace kautham::apps

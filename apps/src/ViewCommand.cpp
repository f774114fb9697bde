// `kautham view PLAN -o plan.html`: the plan file as an animated, self-contained HTML page.
// `kautham view PROBLEM.xml`: the problem's start scene in the same page, to see what was written.

#include <cstdint>
#include <limits>

#include <fmt/format.h>

#include "Commands.h"
#include "KauthamPlanners.h"
#include "NumberOption.h"
#include "OutputFile.h"
#include "PackagePathOption.h"
#include "PlanFile.h"
#include "PlanViewer.h"
#include "TreePicture.h"
#include "kautham/core/ProblemLoader.h"
#include "kautham/physics/Replay.h"

namespace kautham::apps {

namespace {

struct ViewOptions {
  std::string plan;
  std::string output;
  std::string tree;
  std::string threeDir;
  std::vector<std::string> modelDirs;
  std::vector<std::string> packagePaths;
  std::size_t query = 0;
};

/// A problem file's start: the scene as loaded, the robot at its <Init>, the goal region shown,
/// as a plan of no controls. The start is not rejected here: what is wrong with it (objects
/// that interpenetrate, a broken rule) is printed, so the page shows what the author wrote.
nlohmann::json startScene(const ViewOptions& options) {
  applyPackagePaths(options.packagePaths);
  const std::vector<std::filesystem::path> modelDirs(options.modelDirs.begin(),
                                                     options.modelDirs.end());
  const core::Problem problem = core::loadProblem(options.plan, modelDirs);
  if (options.query >= problem.queries.size())
    throw std::invalid_argument(fmt::format("--query {}: the problem has {} queries", options.query,
                                            problem.queries.size()));
  const planners::PlanRequest request =
      planners::makeRequest(problem, plannerToUse(problem, std::nullopt, /*lenient=*/true), {}, 1);
  physics::PlanningContext context(problem, options.query, request.propagation());
  const physics::ReplayResult replay = physics::replay(context, {});
  nlohmann::json plan = planToJson(context, request, planners::PlanOutcome{}, replay);
  fmt::print("start     {}, query {}: {}\n", problem.name, problem.queries[options.query].name,
             context.startViolation() == physics::Violation::None
                 ? std::string("valid")
                 : std::string("INVALID: ") + physics::toString(context.startViolation()));
  nlohmann::json overlaps = nlohmann::json::array();
  for (const physics::Overlap& o : context.startOverlaps()) {
    fmt::print("overlap   {} and {} ({:.1f} mm)\n", o.first, o.second, 1000.0 * o.depth);
    overlaps.push_back({{"first", o.first}, {"second", o.second}, {"depth", o.depth}});
  }
  plan["start_scene"] = {{"overlaps", overlaps},
                         {"violation", physics::toString(context.startViolation())}};
  return plan;
}

bool isProblemFile(const std::string& file) {
  return std::filesystem::path(file).extension() == ".xml";
}

void writeTree(const nlohmann::json& plan, const ViewOptions& options) {
  if (!plan.contains("tree") || !plan.contains("goal"))
    throw ViewError(options.plan + ": this plan file has no search tree; plan it again");
  std::string svg;
  try {
    svg = treeToSvg(plan);
  } catch (const nlohmann::json::exception& e) {
    // The page checks each field it reads; the picture reads the tree's and the goal's as
    // `kautham plan` writes them, so a file edited or cut short is refused here as a whole.
    throw ViewError(options.plan + ": the plan's \"tree\" or \"goal\" is not as `kautham plan` " +
                    "writes it (" + e.what() + "); plan it again");
  }
  writeTextFile(options.tree, svg);
  fmt::print("wrote     {}\n", options.tree);
}

int runView(const ViewOptions& options) {
  // The page is written unless only the tree picture was asked for.
  const bool page = !options.output.empty() || options.tree.empty();
  if (!options.output.empty()) requireOutputFile(options.output, "-o");
  if (!options.tree.empty()) requireOutputFile(options.tree, "--tree");
  const std::filesystem::path threeDir = page ? findThreeDir(options.threeDir) : "";
  const nlohmann::json plan =
      isProblemFile(options.plan) ? startScene(options) : readPlanForView(options.plan);
  if (!options.tree.empty()) writeTree(plan, options);
  if (!page) return kExitSolved;
  const std::filesystem::path output =
      options.output.empty() ? std::filesystem::path(options.plan).replace_extension(".html")
                             : std::filesystem::path(options.output);
  writeTextFile(output, planToHtml(plan, threeDir));
  fmt::print("wrote     {}\n", output.string());
  return kExitSolved;
}

}  // namespace

void addViewCommand(CLI::App& app, int& exitCode) {
  auto options = std::make_shared<ViewOptions>();
  CLI::App* command = app.add_subcommand(
      "view",
      "Write a plan file as an animated HTML page (self-contained, works offline), or a "
      "problem file's start scene");
  command
      ->add_option("plan", options->plan,
                   "plan file (JSON, from `kautham plan -o`), or a problem file (.xml): its start")
      ->required();
  command->add_option("--model-dir", options->modelDirs, "extra folder to search for models")
      ->check(CLI::ExistingDirectory)
      ->allow_extra_args(false);
  addPackagePathOption(*command, options->packagePaths);
  command->add_option("--query", options->query, "the query whose start a problem file shows")
      ->capture_default_str()
      ->check(wholeNumberRange(0, std::numeric_limits<std::uint32_t>::max()));
  command->add_option(
      "-o,--output", options->output,
      "HTML file to write (default: the plan or problem file with extension .html)");
  command->add_option("--tree", options->tree,
                      "also write an SVG picture of the search tree seen from above");
  command->add_option("--three-dir", options->threeDir,
                      "folder with three.min.js and examples/js/controls/OrbitControls.js "
                      "(default: " +
                          kDefaultThreeDir.string() + ", from Debian's libjs-three)");
  command->footer(
      "Exit codes: 0 written, 2 bad input.\nExample: kautham view out/plan.json -o "
      "out/plan.html --tree out/tree.svg");
  command->callback(
      [options, &exitCode] { exitCode = runReportingErrors([&] { return runView(*options); }); });
}

}  // namespace kautham::apps

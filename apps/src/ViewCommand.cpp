// `kautham view PLAN -o plan.html`: the plan file as an animated, self-contained HTML page.

#include <fmt/format.h>

#include "Commands.h"
#include "PlanViewer.h"
#include "TreePicture.h"

namespace kautham::apps {

namespace {

struct ViewOptions {
  std::string plan;
  std::string output;
  std::string tree;
  std::string threeDir;
};

void writeTree(const nlohmann::json& plan, const ViewOptions& options) {
  if (!plan.contains("tree") || !plan.contains("goal"))
    throw ViewError(options.plan + ": this plan file has no search tree; plan it again");
  writeTextFile(options.tree, treeToSvg(plan));
  fmt::print("wrote     {}\n", options.tree);
}

int runView(const ViewOptions& options) {
  // The page is written unless only the tree picture was asked for.
  const bool page = !options.output.empty() || options.tree.empty();
  const std::filesystem::path threeDir = page ? findThreeDir(options.threeDir) : "";
  const nlohmann::json plan = readPlanForView(options.plan);
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
      "view", "Write a plan file as an animated HTML page (self-contained, works offline)");
  command->add_option("plan", options->plan, "plan file (JSON, from `kautham plan -o`)")
      ->required();
  command->add_option("-o,--output", options->output,
                      "HTML file to write (default: the plan file with extension .html)");
  command->add_option("--tree", options->tree,
                      "also write an SVG picture of the search tree seen from above");
  command->add_option("--three-dir", options->threeDir,
                      "folder with three.min.js and examples/js/controls/OrbitControls.js "
                      "(default: " +
                          kDefaultThreeDir.string() + ", from Debian's libjs-three)");
  command->callback(
      [options, &exitCode] { exitCode = runReportingErrors([&] { return runView(*options); }); });
}

}  // namespace kautham::apps

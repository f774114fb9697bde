// `kautham generate clutter`: write a problem file with a robot, a target glass and N movable
// cans placed at random, reproducibly from a seed (docs/scenes.md).

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <fmt/format.h>

#include "ClutterGenerator.h"
#include "Commands.h"

namespace kautham::apps {

namespace {

namespace fs = std::filesystem;

struct GenerateOptions {
  ClutterOptions clutter;
  std::string output;
  bool force = false;
};

int runGenerateClutter(const GenerateOptions& options) {
  const fs::path output(options.output);
  if (fs::exists(output) && !options.force)
    throw std::invalid_argument(
        fmt::format("{} exists already; use --force to overwrite it", options.output));
  if (fs::is_directory(output))
    throw std::invalid_argument(fmt::format("{} is a folder, not a file", options.output));

  const std::vector<CanPlacement> cans = placeClutter(options.clutter);
  // The file name, not the folder, goes into the file: the same options give the same bytes
  // wherever the file is written.
  const std::string name = output.filename().string();
  const std::string xml = clutterProblemXml(options.clutter, cans, output.stem().string(),
                                            clutterCommandLine(options.clutter, name));

  if (output.has_parent_path()) fs::create_directories(output.parent_path());
  std::ofstream out(output, std::ios::binary);
  out << xml;
  out.close();
  if (!out) throw std::runtime_error(fmt::format("could not write {}", options.output));

  const auto blockers =
      std::count_if(cans.begin(), cans.end(), [](const CanPlacement& c) { return c.blocker; });
  fmt::print("wrote     {}: {}, {} cans ({} on the approach to the goal), seed {}\n",
             options.output, options.clutter.robot, cans.size(), blockers, options.clutter.seed);
  return kExitSolved;
}

}  // namespace

void addGenerateCommand(CLI::App& app, int& exitCode) {
  CLI::App* generate = app.add_subcommand("generate", "Write generated problem files");
  generate->require_subcommand(1);

  auto options = std::make_shared<GenerateOptions>();
  CLI::App* clutter = generate->add_subcommand(
      "clutter", "A robot, a target glass and N movable cans on a table, reproducible by seed");
  clutter->add_option("-r,--robot", options->clutter.robot, "the robot")
      ->required()
      ->check(CLI::IsMember(clutterRobots()));
  clutter->add_option("-n,--objects", options->clutter.objects, "number of movable cans")
      ->required()
      ->check(CLI::Range(0, kMaxClutterObjects));
  clutter->add_option("-s,--seed", options->clutter.seed, "random seed: same seed, same scene")
      ->capture_default_str();
  clutter->add_option("-t,--target", options->clutter.target, "the object to grasp")
      ->capture_default_str()
      ->check(CLI::IsMember({"glass"}));
  clutter->add_option("-g,--gap", options->clutter.gap, "least distance between two objects (m)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 0.2));
  clutter->add_option("-o,--output", options->output, "problem file to write (XML)")->required();
  clutter->add_flag("-f,--force", options->force, "overwrite the output file if it exists");
  clutter->footer(
      "Example: kautham generate clutter --robot kuka --objects 10 --seed 3 -o "
      "problems/kuka_cans_10.xml");
  clutter->callback([options, &exitCode] {
    exitCode = runReportingErrors([&] { return runGenerateClutter(*options); });
  });
}

}  // namespace kautham::apps

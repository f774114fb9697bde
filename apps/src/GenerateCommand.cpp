// `kautham generate clutter`: write a problem file with a robot, a target glass and N movable
// cans placed at random, reproducibly from a seed (docs/scenes.md).

#include <algorithm>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "ClutterGenerator.h"
#include "Commands.h"
#include "NumberOption.h"
#include "OutputFile.h"
#include "SideGraspClutter.h"

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
  requireOutputFile(output, "-o");
  if (fs::exists(output) && !options.force)
    throw std::invalid_argument(
        fmt::format("{} exists already; use --force to overwrite it", options.output));

  // The file name, not the folder, goes into the file: the same options give the same bytes
  // wherever the file is written.
  const std::string name = output.filename().string();
  const std::string command = clutterCommandLine(options.clutter, name);
  std::string xml;
  std::size_t objects = 0;
  long blockers = 0;
  if (options.clutter.layout == "top") {
    if (options.clutter.mix) throw std::invalid_argument("--mix needs the side layout");
    const std::vector<CanPlacement> cans = placeClutter(options.clutter);
    xml = clutterProblemXml(options.clutter, cans, output.stem().string(), command);
    objects = cans.size();
    blockers = std::count_if(cans.begin(), cans.end(), [](auto& c) { return c.blocker; });
  } else {
    const std::vector<SceneObject> placed = placeSideGraspClutter(options.clutter);
    xml = sideGraspProblemXml(options.clutter, placed, output.stem().string(), command);
    objects = placed.size();
    blockers = std::count_if(placed.begin(), placed.end(), [](auto& o) { return o.blocker; });
  }

  writeTextFile(output, xml);

  fmt::print("wrote     {}: {}, {} layout, {} objects ({} on the approach to the goal), seed {}\n",
             options.output, options.clutter.robot, options.clutter.layout, objects, blockers,
             options.clutter.seed);
  return kExitSolved;
}

}  // namespace

void addGenerateCommand(CLI::App& app, int& exitCode) {
  CLI::App* generate = app.add_subcommand("generate", "Write generated problem files");
  generate->require_subcommand(1);
  generate->footer("Exit codes: 0 written, 2 bad input.");

  auto options = std::make_shared<GenerateOptions>();
  CLI::App* clutter = generate->add_subcommand(
      "clutter", "A robot, a target and N movable objects on a table, reproducible by seed");
  clutter->add_option("-r,--robot", options->clutter.robot, "the robot")
      ->required()
      ->check(CLI::IsMember(clutterRobots()));
  clutter->add_option("-n,--objects", options->clutter.objects, "number of movable cans")
      ->required()
      ->check(wholeNumberRange(0, kMaxClutterObjects));
  clutter->add_option("-s,--seed", options->clutter.seed, "random seed: same seed, same scene")
      ->capture_default_str()
      ->check(seedRange(std::numeric_limits<std::uint64_t>::max()));
  clutter->add_option("-t,--target", options->clutter.target, "the object to grasp")
      ->capture_default_str()
      ->check(CLI::IsMember({"glass"}));
  clutter->add_option("-g,--gap", options->clutter.gap, "least distance between two objects (m)")
      ->capture_default_str()
      ->check(numberRange(0.0, 0.2));
  clutter
      ->add_option("-l,--layout", options->clutter.layout,
                   "side: the dense suite, a side pre-grasp (kuka_clutter_N); top: the "
                   "earlier top-down suite (kuka_cans_N)")
      ->capture_default_str()
      ->check(CLI::IsMember({"side", "top"}));
  clutter->add_flag("-m,--mix", options->clutter.mix,
                    "side layout: a bottle, then boxes and cans alternating, instead of cans");
  clutter->add_option("-o,--output", options->output, "problem file to write (XML)")->required();
  clutter->add_flag("-f,--force", options->force, "overwrite the output file if it exists");
  clutter->footer(
      "Exit codes: 0 written, 2 bad input (or too many objects for the zone).\n"
      "Example: kautham generate clutter --robot kuka --objects 10 --seed 3 -o "
      "problems/kuka_clutter_10.xml");
  clutter->callback([options, &exitCode] {
    exitCode = runReportingErrors([&] { return runGenerateClutter(*options); });
  });
}

}  // namespace kautham::apps

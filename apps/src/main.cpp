#include <iostream>

#include <ompl/util/Console.h>

#include "Commands.h"
#include "kautham/core/Version.h"

int main(int argc, char** argv) {
  CLI::App app{"kautham: physics-based motion planning for grasping in clutter"};
  app.set_version_flag("--version", std::string("kautham ") + kautham::core::version());
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 solved, 1 ran but not solved, 2 bad input.\n"
      "Example: kautham plan problems/pusher_cans_5.xml --seed 1 -o out/plan.json\n"
      "         kautham view out/plan.json -o out/plan.html\n"
      "Problem files: docs/problem-format.md");
  app.fallthrough();

  // OMPL's informational messages would drown our summary; its warnings and errors stay.
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);

  int exitCode = kautham::apps::kExitSolved;
  kautham::apps::addPlanCommand(app, exitCode);
  kautham::apps::addCheckCommand(app, exitCode);
  kautham::apps::addPlannersCommand(app, exitCode);
  kautham::apps::addGenerateCommand(app, exitCode);
  kautham::apps::addViewCommand(app, exitCode);
  kautham::apps::addValidateCommand(app, exitCode);
  kautham::apps::addBenchCommand(app, exitCode);
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kautham::apps::kExitBadInput;
  }
  return exitCode;
}

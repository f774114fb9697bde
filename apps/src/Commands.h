#pragma once

// The subcommands of the `kautham` console program. Each adds itself to the CLI11 app and
// sets `exitCode` when it runs: 0 success or solved, 1 ran but not solved, 2 bad input.

#include <functional>

#include <CLI/CLI.hpp>

namespace kautham::apps {

void addBenchCommand(CLI::App& app, int& exitCode);
void addCheckCommand(CLI::App& app, int& exitCode);
void addGenerateCommand(CLI::App& app, int& exitCode);
void addPlanCommand(CLI::App& app, int& exitCode);
void addPlannersCommand(CLI::App& app, int& exitCode);
void addViewCommand(CLI::App& app, int& exitCode);
void addValidateCommand(CLI::App& app, int& exitCode);

constexpr int kExitSolved = 0;
constexpr int kExitNotSolved = 1;
constexpr int kExitBadInput = 2;

/// Runs a subcommand's work and turns what it throws into a message and an exit code: bad
/// input (a problem, plan or parameter error) gives 2, any other failure 1.
int runReportingErrors(const std::function<int()>& work);

}  // namespace kautham::apps

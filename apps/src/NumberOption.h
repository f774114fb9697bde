#pragma once

// Checks for options that take a number. CLI11 says "Value abc not in range" for a word given
// where a number belongs, "Could not convert" for a seed out of range, and wraps "--query -1"
// round to 18446744073709551615; these say what the option must be and echo what was given.

#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

namespace kautham::apps {

/// Checks an option's text before CLI11 converts it: a whole number in [min, max].
CLI::Validator wholeNumberRange(std::uint64_t min, std::uint64_t max);

/// Checks an option's text before CLI11 converts it: a finite number in [min, max].
CLI::Validator numberRange(double min, double max);

/// `--seed`: a whole number in the range the command's random streams take, [0, max].
CLI::Validator seedRange(std::uint64_t max);

/// wholeNumberRange's message for `text`, empty when it passes (for tests).
std::string wholeNumberError(const std::string& text, std::uint64_t min, std::uint64_t max);

/// numberRange's message for `text`, empty when it passes (for tests).
std::string numberError(const std::string& text, double min, double max);

/// seedRange's message for `text`, empty when it is a seed in [0, max] (for tests).
std::string seedRangeError(const std::string& text, std::uint64_t max);

}  // namespace kautham::apps

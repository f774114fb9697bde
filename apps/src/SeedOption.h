#pragma once

// `--seed`: a whole number in the range the command's random streams take. CLI11 says only
// "Could not convert" for a seed out of range; this says what a seed must be.

#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

namespace kautham::apps {

/// Checks --seed's text before CLI11 converts it: an integer in [0, max].
CLI::Validator seedRange(std::uint64_t max);

/// The check's message for `text`, empty when it is a seed in [0, max] (for tests).
std::string seedRangeError(const std::string& text, std::uint64_t max);

}  // namespace kautham::apps

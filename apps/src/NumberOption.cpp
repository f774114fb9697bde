#include "NumberOption.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <optional>

#include <fmt/format.h>

namespace kautham::apps {

namespace {

std::optional<std::uint64_t> wholeNumber(const std::string& text) {
  // Digits only: strtoull would accept a sign (and wrap "-1" round to the largest value).
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos)
    return std::nullopt;
  errno = 0;
  const unsigned long long value = std::strtoull(text.c_str(), nullptr, 10);
  if (errno != 0) return std::nullopt;
  return value;
}

std::optional<double> finiteNumber(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (errno != 0 || end != text.c_str() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

}  // namespace

std::string wholeNumberError(const std::string& text, std::uint64_t min, std::uint64_t max) {
  const auto value = wholeNumber(text);
  if (value && *value >= min && *value <= max) return "";
  return fmt::format("expected an integer in [{}, {}], got '{}'", min, max, text);
}

std::string numberError(const std::string& text, double min, double max) {
  const auto value = finiteNumber(text);
  if (value && *value >= min && *value <= max) return "";
  return fmt::format("expected a number in [{}, {}], got '{}'", min, max, text);
}

std::string seedRangeError(const std::string& text, std::uint64_t max) {
  if (wholeNumberError(text, 0, max).empty()) return "";
  return fmt::format("the seed must be an integer in [0, {}], got '{}'", max, text);
}

CLI::Validator wholeNumberRange(std::uint64_t min, std::uint64_t max) {
  return CLI::Validator([min, max](std::string& text) { return wholeNumberError(text, min, max); },
                        fmt::format("INT in [{}, {}]", min, max), "whole number range");
}

CLI::Validator numberRange(double min, double max) {
  return CLI::Validator([min, max](std::string& text) { return numberError(text, min, max); },
                        fmt::format("NUMBER in [{}, {}]", min, max), "number range");
}

CLI::Validator seedRange(std::uint64_t max) {
  return CLI::Validator([max](std::string& text) { return seedRangeError(text, max); },
                        fmt::format("SEED in [0, {}]", max), "seed range");
}

}  // namespace kautham::apps

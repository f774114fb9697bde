#include "SeedOption.h"

#include <cerrno>
#include <cstdlib>

#include <fmt/format.h>

namespace kautham::apps {

std::string seedRangeError(const std::string& text, std::uint64_t max) {
  // Digits only: strtoull would accept a sign (and wrap "-1" round to the largest value).
  if (!text.empty() && text.find_first_not_of("0123456789") == std::string::npos) {
    errno = 0;
    const unsigned long long value = std::strtoull(text.c_str(), nullptr, 10);
    if (errno == 0 && value <= max) return "";
  }
  return fmt::format("the seed must be an integer in [0, {}], got '{}'", max, text);
}

CLI::Validator seedRange(std::uint64_t max) {
  return CLI::Validator([max](std::string& text) { return seedRangeError(text, max); },
                        fmt::format("SEED in [0, {}]", max), "seed range");
}

}  // namespace kautham::apps

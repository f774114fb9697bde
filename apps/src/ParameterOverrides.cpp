#include "ParameterOverrides.h"

#include <stdexcept>

#include <fmt/format.h>

namespace kautham::apps {

std::vector<planners::ParameterOverride> parameterOverrides(const std::vector<std::string>& sets,
                                                            std::optional<double> time,
                                                            std::optional<unsigned> threads) {
  std::vector<planners::ParameterOverride> overrides;
  for (const std::string& text : sets) {
    const auto equals = text.find('=');
    if (equals == std::string::npos || equals == 0)
      throw std::invalid_argument("--set expects NAME=VALUE, got '" + text + "'");
    overrides.emplace_back(text.substr(0, equals), text.substr(equals + 1));
  }
  if (time) overrides.emplace_back("time_limit", fmt::format("{}", *time));
  if (threads) overrides.emplace_back("threads", fmt::format("{}", *threads));
  return overrides;
}

}  // namespace kautham::apps

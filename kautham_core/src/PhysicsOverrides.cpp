#include "kautham/core/PhysicsOverrides.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <map>
#include <sstream>
#include <stdexcept>

#include "kautham/core/Parameter.h"

namespace kautham::core {

namespace {

/// One number, the whole text, finite.
double parseNumber(const std::string& text) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(begin, &end);
  while (end && *end == ' ') ++end;
  if (end == begin || *end != '\0' || errno == ERANGE || !std::isfinite(value))
    throw std::invalid_argument("expected a number, got '" + text + "'");
  return value;
}

int parseWholeNumber(const std::string& text) {
  const double value = parseNumber(text);
  if (value != std::floor(value) || std::abs(value) > 1e9)
    throw std::invalid_argument("expected a whole number, got '" + text + "'");
  return static_cast<int>(value);
}

bool parseFlag(const std::string& text) {
  if (const std::optional<bool> flag = flagWord(text)) return *flag;
  throw std::invalid_argument("expected true or false, got '" + text + "'");
}

Eigen::Vector3d parseVector(const std::string& text) {
  std::istringstream in(text);
  std::vector<double> values;
  for (std::string word; in >> word;) values.push_back(parseNumber(word));
  if (values.size() != 3) throw std::invalid_argument("expected three numbers, got '" + text + "'");
  return {values[0], values[1], values[2]};
}

using Setter = std::function<void(PhysicsSettings&, const std::string&)>;

/// The <Physics> attributes, by name, and how each is read.
const std::map<std::string, Setter>& setters() {
  static const std::map<std::string, Setter> table{
      {"stepSize", [](PhysicsSettings& p, const std::string& v) { p.stepSize = parseNumber(v); }},
      {"gravity", [](PhysicsSettings& p, const std::string& v) { p.gravity = parseVector(v); }},
      {"maxContacts",
       [](PhysicsSettings& p, const std::string& v) { p.maxContacts = parseWholeNumber(v); }},
      {"solverIterations",
       [](PhysicsSettings& p, const std::string& v) { p.solverIterations = parseWholeNumber(v); }},
      {"overRelaxation",
       [](PhysicsSettings& p, const std::string& v) { p.overRelaxation = parseNumber(v); }},
      {"friction", [](PhysicsSettings& p, const std::string& v) { p.friction = parseNumber(v); }},
      {"erp", [](PhysicsSettings& p, const std::string& v) { p.erp = parseNumber(v); }},
      {"cfm", [](PhysicsSettings& p, const std::string& v) { p.cfm = parseNumber(v); }},
      {"sleep", [](PhysicsSettings& p, const std::string& v) { p.sleep = parseFlag(v); }},
      {"sleepSpeed",
       [](PhysicsSettings& p, const std::string& v) { p.sleepSpeed = parseNumber(v); }},
      {"sleepSteps",
       [](PhysicsSettings& p, const std::string& v) { p.sleepSteps = parseWholeNumber(v); }},
  };
  return table;
}

std::string attributeNames() {
  std::string names;
  for (const auto& [name, setter] : setters()) names += (names.empty() ? "" : ", ") + name;
  return names;
}

}  // namespace

std::optional<std::string> physicsSettingsError(const PhysicsSettings& p) {
  if (!(p.stepSize > 0.0)) return "attribute stepSize must be positive";
  if (p.stepSize > 0.1) return "stepSize must be at most 0.1 s for a stable simulation";
  if (!p.gravity.allFinite()) return "gravity must be three finite numbers";
  if (p.maxContacts < 1 || p.maxContacts > 64) return "maxContacts must be in [1, 64]";
  if (p.solverIterations < 1 || p.solverIterations > 1000)
    return "solverIterations must be in [1, 1000]";
  // Gauss-Seidel with over-relaxation converges only for factors strictly between 0 and 2.
  if (!(p.overRelaxation > 0.0 && p.overRelaxation < 2.0))
    return "overRelaxation must be above 0 and below 2 (ODE's default is 1.3)";
  if (!(p.friction >= 0.0)) return "attribute friction must be non-negative";
  if (!(p.erp >= 0.0)) return "attribute erp must be non-negative";
  if (p.erp > 1.0) return "erp must be in [0, 1]";
  if (!(p.cfm >= 0.0)) return "attribute cfm must be non-negative";
  if (!(p.sleepSpeed > 0.0)) return "attribute sleepSpeed must be positive";
  if (p.sleepSteps < 1) return "sleepSteps must be at least 1";
  return std::nullopt;
}

void applyPhysicsOverrides(PhysicsSettings& settings, const std::vector<std::string>& assignments) {
  for (const std::string& assignment : assignments) {
    const auto equals = assignment.find('=');
    const std::string name = assignment.substr(0, equals);
    const auto setter = setters().find(name);
    if (equals == std::string::npos || setter == setters().end())
      throw std::invalid_argument(
          "--physics " + assignment +
          ": expected NAME=VALUE with NAME an attribute of <Physics>: " + attributeNames());
    try {
      setter->second(settings, assignment.substr(equals + 1));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("--physics " + assignment + ": " + e.what());
    }
    if (const std::optional<std::string> error = physicsSettingsError(settings))
      throw std::invalid_argument("--physics " + assignment + ": " + *error);
  }
}

}  // namespace kautham::core

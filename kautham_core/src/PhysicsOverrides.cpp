#include "kautham/core/PhysicsOverrides.h"

#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <variant>

#include "kautham/core/Parameter.h"

namespace kautham::core {

namespace {

double parseNumber(const std::string& text) {
  if (const std::optional<double> number = numberWord(text)) return *number;
  if (beyondDouble(text))
    throw std::invalid_argument("out of range: " + text +
                                " is beyond the largest number a double holds (about 1.8e308)");
  throw std::invalid_argument("expected a number, got '" + text + "'");
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

/// A <Physics> attribute: the field it sets; its type says how its text is read.
using Field = std::variant<double PhysicsSettings::*, int PhysicsSettings::*,
                           bool PhysicsSettings::*, Eigen::Vector3d PhysicsSettings::*>;

const std::map<std::string, Field>& fields() {
  static const std::map<std::string, Field> table{
      {"stepSize", &PhysicsSettings::stepSize},
      {"gravity", &PhysicsSettings::gravity},
      {"maxContacts", &PhysicsSettings::maxContacts},
      {"solverIterations", &PhysicsSettings::solverIterations},
      {"overRelaxation", &PhysicsSettings::overRelaxation},
      {"friction", &PhysicsSettings::friction},
      {"erp", &PhysicsSettings::erp},
      {"cfm", &PhysicsSettings::cfm},
      {"sleep", &PhysicsSettings::sleep},
      {"sleepSpeed", &PhysicsSettings::sleepSpeed},
      {"sleepSteps", &PhysicsSettings::sleepSteps},
  };
  return table;
}

void set(PhysicsSettings& settings, const Field& field, const std::string& text) {
  std::visit(
      [&](auto member) {
        using Value = std::decay_t<decltype(settings.*member)>;
        if constexpr (std::is_same_v<Value, double>) settings.*member = parseNumber(text);
        if constexpr (std::is_same_v<Value, int>) settings.*member = parseWholeNumber(text);
        if constexpr (std::is_same_v<Value, bool>) settings.*member = parseFlag(text);
        if constexpr (std::is_same_v<Value, Eigen::Vector3d>) settings.*member = parseVector(text);
      },
      field);
}

std::string attributeNames() {
  std::string names;
  for (const auto& [name, field] : fields()) names += (names.empty() ? "" : ", ") + name;
  return names;
}

// The bounds physicsSettingsError() holds a simulation to (see there why).
constexpr double kSmallestStep = 1e-4;      // s
constexpr double kLargestGravity = 1000.0;  // m/s^2

}  // namespace

std::optional<std::string> physicsSettingsError(const PhysicsSettings& p) {
  if (!(p.stepSize > 0.0)) return "attribute stepSize must be positive";
  if (p.stepSize > 0.1) return "stepSize must be at most 0.1 s for a stable simulation";
  // Every world settles its start for a simulated second before planning: at 1e-9 s that is a
  // billion steps, and the run hangs before the time limit is ever looked at.
  if (p.stepSize < kSmallestStep)
    return "stepSize must be at least 0.0001 s (a simulated second would take over 10 000 "
           "steps; the shipped problems use 0.01)";
  if (!p.gravity.allFinite()) return "gravity must be three finite numbers";
  // ODE aborts the process on the velocities a gravity of 1e300 m/s^2 gives in one step.
  if (p.gravity.norm() > kLargestGravity)
    return "gravity must be at most 1000 m/s^2 in magnitude (the Earth's is 9.81)";
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
    const auto field = fields().find(name);
    if (equals == std::string::npos || field == fields().end())
      throw std::invalid_argument(
          "--physics " + assignment +
          ": expected NAME=VALUE with NAME an attribute of <Physics>: " + attributeNames());
    try {
      set(settings, field->second, assignment.substr(equals + 1));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("--physics " + assignment + ": " + e.what());
    }
    if (const std::optional<std::string> error = physicsSettingsError(settings))
      throw std::invalid_argument("--physics " + assignment + ": " + *error);
  }
}

}  // namespace kautham::core

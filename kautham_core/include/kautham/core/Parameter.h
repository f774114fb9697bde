#pragma once

#include <map>
#include <string>
#include <vector>

namespace kautham::core {

enum class ParameterType { Real, Integer, Boolean };

/// A typed, documented planner parameter: what `kautham planners` lists.
struct ParameterSpec {
  std::string name;  ///< canonical name, snake_case
  ParameterType type = ParameterType::Real;
  double defaultValue = 0.0;
  double min = 0.0;
  double max = 0.0;
  std::string description;           ///< one line
  std::vector<std::string> aliases;  ///< other accepted names, e.g. Kautham's "Goal Bias"

  bool answersTo(const std::string& someName) const;
  std::string formatValue(double value) const;
};

/// Values for a list of parameter specs; every value is typed and range-checked when set.
class ParameterSet {
 public:
  ParameterSet() = default;
  explicit ParameterSet(std::vector<ParameterSpec> specs);

  /// True if `name` (or an alias) is one of the specs.
  bool has(const std::string& name) const;
  /// Parses and sets a value. Throws std::invalid_argument with a message a user can act on.
  void set(const std::string& name, const std::string& text);

  double real(const std::string& name) const;
  int integer(const std::string& name) const;
  bool boolean(const std::string& name) const;

  const std::vector<ParameterSpec>& specs() const { return specs_; }
  /// Every parameter with its current value, as text, by canonical name.
  std::map<std::string, std::string> values() const;

 private:
  const ParameterSpec& spec(const std::string& name) const;
  std::string listOfNames() const;

  std::vector<ParameterSpec> specs_;
  std::map<std::string, double> values_;
};

}  // namespace kautham::core

#pragma once

#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace kautham::core {

enum class ParameterType { Real, Integer, Boolean };

/// A yes/no word as users write it, any case: true, 1, yes, on or false, 0, no, off (none
/// otherwise). Planner flags and the problem file's flag attributes both read flags so.
std::optional<bool> flagWord(const std::string& text);
/// A number as users write it: the whole text one finite number (none otherwise). Planner
/// parameters and --physics values both read numbers so.
std::optional<double> numberWord(const std::string& text);
/// Whether `text` is a decimal number too large for a double (1e400): it is a number, just out
/// of range, and a message should say so rather than "expects a number".
bool beyondDouble(const std::string& text);

/// A typed, documented planner parameter: what `kautham planners` lists. Declare one with the
/// named builders of `Parameter` rather than by position.
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

/// Throws std::logic_error naming the parameter unless the spec is well formed: a snake_case
/// name, a description, min <= default <= max, whole numbers for an integer, 0 or 1 for a flag.
void checkSpec(const ParameterSpec& spec);
/// checkSpec for each, and no name or alias used twice in the list.
void checkSpecs(const std::vector<ParameterSpec>& specs);

/// Declares a parameter with named builders, so that a declaration says what each number is:
///
///     Parameter::real("goal_bias").byDefault(0.05).range(0, 1)
///         .describe("probability of expanding towards the goal").alias("Goal Bias")
///
/// A flag's range is [0, 1] (false, true); reals and integers need one.
class Parameter {
 public:
  static Parameter real(std::string name) {
    return Parameter(std::move(name), ParameterType::Real);
  }
  static Parameter integer(std::string name) {
    return Parameter(std::move(name), ParameterType::Integer);
  }
  static Parameter flag(std::string name) {
    Parameter p(std::move(name), ParameterType::Boolean);
    p.spec_.max = 1.0;
    return p;
  }

  Parameter byDefault(double value) const {
    return with([&](ParameterSpec& s) { s.defaultValue = value; });
  }
  Parameter range(double min, double max) const {
    return with([&](ParameterSpec& s) {
      s.min = min;
      s.max = max;
    });
  }
  Parameter describe(std::string text) const {
    return with([&](ParameterSpec& s) { s.description = std::move(text); });
  }
  /// Another accepted name (Kautham's "Goal Bias", the paper's "k"); repeatable.
  Parameter alias(std::string other) const {
    return with([&](ParameterSpec& s) { s.aliases.push_back(std::move(other)); });
  }

  const ParameterSpec& spec() const { return spec_; }
  operator ParameterSpec() const { return spec_; }  // NOLINT: a Parameter is a spec being built

 private:
  Parameter(std::string name, ParameterType type) {
    spec_.name = std::move(name);
    spec_.type = type;
  }
  template <typename Change>
  Parameter with(Change change) const {
    Parameter copy = *this;
    change(copy.spec_);
    return copy;
  }

  ParameterSpec spec_;
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

/// The parameters of a settings struct, each declared once with its field: the table both lists
/// the specs (for the registry, `kautham planners`, OMPL) and fills a struct from values, so no
/// field is copied by hand.
///
///     struct MySettings { double goalBias; unsigned candidates; };
///     const auto table = SettingsParameters<MySettings>()
///         .add(&MySettings::goalBias, Parameter::real("goal_bias").byDefault(0.05).range(0, 1)...)
///         .add(&MySettings::candidates, Parameter::integer("candidates")...);
///     MySettings settings = table.read(values);
///
/// A field is a double (real), an int or unsigned (integer) or a bool (flag). `add` without a
/// field declares a parameter the framework itself applies (the projection's `cell_size`).
/// The struct's own initial values play no part: every field comes from the table.
template <typename Settings>
class SettingsParameters {
 public:
  template <typename Field>
  SettingsParameters& add(Field Settings::*field, const Parameter& parameter) {
    const ParameterSpec& spec = parameter.spec();
    checkFieldType<Field>(spec);
    checkAdding(spec);
    specs_.push_back(spec);
    assign_.push_back([field, name = spec.name](Settings& settings, const ParameterSet& values) {
      if constexpr (std::is_same_v<Field, bool>)
        settings.*field = values.boolean(name);
      else if constexpr (std::is_integral_v<Field>)
        settings.*field = static_cast<Field>(values.integer(name));
      else
        settings.*field = values.real(name);
    });
    return *this;
  }
  /// Every parameter of `inner`, a table of the struct's member `member`: a planner whose
  /// settings hold another's (a diagnosis that takes p-KPIECE's parameters and some of its own)
  /// declares them once, where the other does.
  template <typename Inner>
  SettingsParameters& include(Inner Settings::*member, const SettingsParameters<Inner>& inner) {
    std::vector<ParameterSpec> all = specs_;
    all.insert(all.end(), inner.specs().begin(), inner.specs().end());
    checkSpecs(all);
    specs_ = std::move(all);
    assign_.push_back([member, inner](Settings& settings, const ParameterSet& values) {
      settings.*member = inner.read(values);
    });
    return *this;
  }
  /// A parameter with no field of the struct: the framework applies it (see the class).
  SettingsParameters& add(const Parameter& parameter) {
    checkAdding(parameter.spec());
    specs_.push_back(parameter.spec());
    return *this;
  }

  const std::vector<ParameterSpec>& specs() const { return specs_; }

  /// The settings with every field taken from `values` (which must be a set of these specs).
  Settings read(const ParameterSet& values) const {
    Settings settings{};
    for (const auto& assign : assign_) assign(settings, values);
    return settings;
  }
  Settings defaults() const { return read(ParameterSet(specs_)); }

 private:
  /// checkSpecs of the table with `spec` added; the table is unchanged if that throws.
  void checkAdding(const ParameterSpec& spec) const {
    std::vector<ParameterSpec> all = specs_;
    all.push_back(spec);
    checkSpecs(all);
  }

  template <typename Field>
  static void checkFieldType(const ParameterSpec& spec) {
    static_assert(std::is_same_v<Field, bool> || std::is_same_v<Field, double> ||
                      std::is_same_v<Field, int> || std::is_same_v<Field, unsigned>,
                  "a parameter's field is a double, an int, an unsigned or a bool");
    const ParameterType wanted = std::is_same_v<Field, bool>     ? ParameterType::Boolean
                                 : std::is_same_v<Field, double> ? ParameterType::Real
                                                                 : ParameterType::Integer;
    if (spec.type != wanted)
      throw std::logic_error("parameter '" + spec.name + "': the field's type does not match (" +
                             "real: double, integer: int or unsigned, flag: bool)");
    if (std::is_same_v<Field, unsigned> && spec.min < 0.0)
      throw std::logic_error("parameter '" + spec.name + "': an unsigned field needs min >= 0");
  }

  std::vector<ParameterSpec> specs_;
  std::vector<std::function<void(Settings&, const ParameterSet&)>> assign_;
};

}  // namespace kautham::core

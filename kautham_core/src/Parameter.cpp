#include "kautham/core/Parameter.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace kautham::core {

bool ParameterSpec::answersTo(const std::string& someName) const {
  return someName == name || std::find(aliases.begin(), aliases.end(), someName) != aliases.end();
}

std::string ParameterSpec::formatValue(double value) const {
  if (type == ParameterType::Boolean) return value != 0.0 ? "true" : "false";
  if (type == ParameterType::Integer) return std::to_string(static_cast<long long>(value));
  std::ostringstream text;
  text.precision(10);
  text << value;
  return text.str();
}

namespace {

bool isSnakeCase(const std::string& name) {
  if (name.empty() || !std::islower(static_cast<unsigned char>(name.front()))) return false;
  return std::all_of(name.begin(), name.end(), [](unsigned char c) {
    return std::islower(c) || std::isdigit(c) || c == '_';
  });
}

bool isWhole(double value) { return std::isfinite(value) && value == std::floor(value); }

}  // namespace

void checkSpec(const ParameterSpec& spec) {
  auto fail = [&](const std::string& what) {
    throw std::logic_error("parameter '" + spec.name + "': " + what);
  };
  if (!isSnakeCase(spec.name)) fail("the name must be snake_case (a-z, 0-9, _)");
  if (spec.description.empty()) fail("no description");
  if (!(spec.min <= spec.max)) fail("its range has min > max (or is not a number)");
  if (!(spec.min <= spec.defaultValue && spec.defaultValue <= spec.max))
    fail("its default " + spec.formatValue(spec.defaultValue) + " is outside [" +
         spec.formatValue(spec.min) + ", " + spec.formatValue(spec.max) + "]");
  if (spec.type == ParameterType::Integer &&
      !(isWhole(spec.defaultValue) && isWhole(spec.min) && isWhole(spec.max)))
    fail("an integer's default and range are whole numbers");
  if (spec.type == ParameterType::Boolean &&
      (spec.min != 0.0 || spec.max != 1.0 || !isWhole(spec.defaultValue)))
    fail("a flag's range is [0, 1] and its default 0 or 1");
  for (const std::string& alias : spec.aliases)
    if (alias.empty() || alias == spec.name) fail("an alias is empty or the name itself");
}

void checkSpecs(const std::vector<ParameterSpec>& specs) {
  for (std::size_t i = 0; i < specs.size(); ++i) {
    checkSpec(specs[i]);
    for (std::size_t j = 0; j < i; ++j) {
      const ParameterSpec& earlier = specs[j];
      if (earlier.answersTo(specs[i].name))
        throw std::logic_error("parameter '" + specs[i].name + "' is declared twice");
      for (const std::string& alias : specs[i].aliases)
        if (earlier.answersTo(alias))
          throw std::logic_error("parameters '" + earlier.name + "' and '" + specs[i].name +
                                 "' both answer to '" + alias + "'");
    }
  }
}

ParameterSet::ParameterSet(std::vector<ParameterSpec> specs) : specs_(std::move(specs)) {
  for (const ParameterSpec& s : specs_) values_[s.name] = s.defaultValue;
}

bool ParameterSet::has(const std::string& name) const {
  return std::any_of(specs_.begin(), specs_.end(),
                     [&](const ParameterSpec& s) { return s.answersTo(name); });
}

const ParameterSpec& ParameterSet::spec(const std::string& name) const {
  for (const ParameterSpec& s : specs_)
    if (s.answersTo(name)) return s;
  throw std::invalid_argument("unknown parameter '" + name + "'; known: " + listOfNames());
}

std::string ParameterSet::listOfNames() const {
  std::string list;
  for (const ParameterSpec& s : specs_) list += (list.empty() ? "" : ", ") + s.name;
  return list.empty() ? "none" : list;
}

namespace {

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

}  // namespace

std::optional<bool> flagWord(const std::string& text) {
  const std::string word = lowercase(text);
  if (word == "true" || word == "1" || word == "yes" || word == "on") return true;
  if (word == "false" || word == "0" || word == "no" || word == "off") return false;
  return std::nullopt;
}

namespace {

bool isDecimal(const std::string& text) {
  // Decimal numbers only: strtod also reads hexadecimal ("0x10" as 16, "0x0.1p0").
  return text.find_first_not_of("0123456789+-.eE \t\n") == std::string::npos;
}

}  // namespace

std::optional<double> numberWord(const std::string& text) {
  if (!isDecimal(text)) return std::nullopt;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0' || !std::isfinite(value)) return std::nullopt;
  return value;
}

bool beyondDouble(const std::string& text) {
  if (!isDecimal(text)) return false;
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  return end != text.c_str() && *end == '\0' && errno == ERANGE && std::isinf(value);
}

namespace {

double parseValue(const ParameterSpec& spec, const std::string& text) {
  if (spec.type == ParameterType::Boolean) {
    if (const std::optional<bool> flag = flagWord(text)) return *flag ? 1.0 : 0.0;
    throw std::invalid_argument("parameter '" + spec.name + "' expects true or false, got '" +
                                text + "'");
  }
  const std::optional<double> number = numberWord(text);
  if (!number && beyondDouble(text))
    throw std::invalid_argument("parameter '" + spec.name + "' is out of range: " + text +
                                " is beyond the largest number a double holds (about 1.8e308); "
                                "it must be in [" +
                                spec.formatValue(spec.min) + ", " + spec.formatValue(spec.max) +
                                "]");
  if (!number)
    throw std::invalid_argument("parameter '" + spec.name + "' expects a number, got '" + text +
                                "'");
  const double value = *number;
  if (spec.type == ParameterType::Integer && value != std::floor(value))
    throw std::invalid_argument("parameter '" + spec.name + "' expects a whole number, got '" +
                                text + "'");
  if (value < spec.min || value > spec.max)
    throw std::invalid_argument("parameter '" + spec.name + "' must be in [" +
                                spec.formatValue(spec.min) + ", " + spec.formatValue(spec.max) +
                                "], got " + text);
  return value;
}

}  // namespace

void ParameterSet::set(const std::string& name, const std::string& text) {
  const ParameterSpec& s = spec(name);
  values_[s.name] = parseValue(s, text);
}

double ParameterSet::real(const std::string& name) const { return values_.at(spec(name).name); }

int ParameterSet::integer(const std::string& name) const {
  return static_cast<int>(values_.at(spec(name).name));
}

bool ParameterSet::boolean(const std::string& name) const {
  return values_.at(spec(name).name) != 0.0;
}

std::map<std::string, std::string> ParameterSet::values() const {
  std::map<std::string, std::string> text;
  for (const ParameterSpec& s : specs_) text[s.name] = s.formatValue(values_.at(s.name));
  return text;
}

}  // namespace kautham::core

#include "PlanControlCheck.h"

#include <cmath>
#include <cstdint>

#include <fmt/format.h>

namespace kautham::apps {

namespace {

using nlohmann::json;

std::optional<std::string> valuesError(const json& values) {
  if (!values.is_array() || values.empty())
    return std::string("needs a \"values\" array of numbers (one per control)");
  for (const json& v : values) {
    if (!v.is_number() || !std::isfinite(v.get<double>()))
      return "\"values\" holds something that is not a finite number: " + v.dump();
    if (std::abs(v.get<double>()) > kMaxControlValue)
      return fmt::format(
          "\"values\" holds {}, outside [-1, 1]: a control value is a fraction of a joint's "
          "velocity limit (or of a control-set column); write values in [-1, 1]",
          v.dump());
  }
  return std::nullopt;
}

/// The steps are what is executed; a duration that says otherwise is a plan edited by hand
/// (or written by another tool) whose author meant something else.
std::optional<std::string> durationError(const json& control, std::uint64_t steps,
                                         double stepSize) {
  if (!control.contains("duration")) return std::nullopt;
  const json& duration = control["duration"];
  const double executed = static_cast<double>(steps) * stepSize;
  if (duration.is_number() && std::abs(duration.get<double>() - executed) <= kDurationTolerance)
    return std::nullopt;
  return fmt::format(
      "\"duration\" {} disagrees with \"steps\" {} x propagation_step_size {:g} s = {:g} s; the "
      "steps are what is executed: make \"duration\" {:g} (or leave it out), or change \"steps\" "
      "to the duration meant",
      duration.dump(), steps, stepSize, executed, executed);
}

}  // namespace

std::optional<std::string> planControlError(const json& control, double stepSize) {
  if (!control.is_object()) return std::string("expected an object with \"values\" and \"steps\"");
  if (auto error = valuesError(control.value("values", json()))) return error;
  const json steps = control.value("steps", json());
  if (!steps.is_number_unsigned() || steps.get<std::uint64_t>() == 0 ||
      steps.get<std::uint64_t>() > 1000000)
    return std::string("\"steps\" must be a whole number of propagation steps in [1, 1000000]");
  return durationError(control, steps.get<std::uint64_t>(), stepSize);
}

}  // namespace kautham::apps

#pragma once

// One control of a plan file (PlanFile.cpp's format), as `kautham validate` executes it and
// `kautham view` draws it: what is wrong with it, so that neither runs a hand-edited or corrupt
// control as given.

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace kautham::apps {

/// Largest |value| of a control: the planners' control space is [-1, 1] per dimension (a
/// fraction of a joint's velocity limit, or of a control-set column); the tolerance only
/// forgives a value rounded when written by hand.
constexpr double kMaxControlValue = 1.0 + 1e-9;
/// Largest difference between a control's "duration" and its steps times the step size (s).
constexpr double kDurationTolerance = 1e-6;

/// What is wrong with `control` (its "values", "steps" and "duration"), or nothing.
/// `stepSize` is the plan's propagation_step_size (s).
std::optional<std::string> planControlError(const nlohmann::json& control, double stepSize);

}  // namespace kautham::apps

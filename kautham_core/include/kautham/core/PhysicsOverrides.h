#pragma once

#include <optional>
#include <string>
#include <vector>

#include "kautham/core/Problem.h"

namespace kautham::core {

/// The first rule `settings` break, if any, worded as for a <Physics> element (the loader
/// reports it with the file and line; --physics with the assignment).
std::optional<std::string> physicsSettingsError(const PhysicsSettings& settings);

/// Sets <Physics> attributes from outside the problem file, each "NAME=VALUE" with NAME an
/// attribute of <Physics> (docs/problem-format.md) and VALUE as the file would write it
/// ("1.7", "true", "0 0 -9.81"), in order, then checks the result as the loader does. This is
/// how `kautham plan --physics` and a bench configuration's "physics" measure another solver
/// setting without a copy of the file. Throws std::invalid_argument naming the assignment.
void applyPhysicsOverrides(PhysicsSettings& settings, const std::vector<std::string>& assignments);

}  // namespace kautham::core

#pragma once

#include <functional>
#include <string>

namespace kautham::core {

/// The project's one channel for warnings: every library message a user should read (ours,
/// urdfdom's, ODE's, libccd's) goes through it to stderr, never stdout, so a pipe of
/// `kautham plan` output stays machine readable.
///
/// warning() prints "warning: MESSAGE"; warnOnce() prints a message only the first time its
/// key is seen in this process (a mesh named once, not once per world built from it).
void warning(const std::string& message);
void warnOnce(const std::string& key, const std::string& message);

/// Replaces where warnings go (tests collect them); an empty function restores stderr.
/// Returns the previous sink.
using WarningSink = std::function<void(const std::string& message)>;
WarningSink setWarningSink(WarningSink sink);

/// Forgets the keys warnOnce() has seen (tests that expect a warning again).
void resetWarnOnce();

}  // namespace kautham::core

#pragma once
// The files the commands write (plans, pages, reports, logs): a path that cannot be a file is
// refused before any work, and a file is written whole or not at all.

#include <filesystem>
#include <string>

namespace kautham::apps {

/// Throws std::invalid_argument (exit 2), naming `option` and `file`, when `file` cannot be
/// written as a plain file: it is a folder, a device or a pipe (which writing would replace), or
/// something on its way that should be a folder is a file. Commands call it before they plan,
/// so that a mistyped -o does not cost the planning time.
void requireOutputFile(const std::filesystem::path& file, const std::string& option);

/// Throws std::invalid_argument (exit 2), naming `option` and `folder`, when `folder` cannot be
/// an output folder: it is a file, or lies among the system's devices, or something on its way
/// is a file. `kautham bench` calls it before any run.
void requireOutputFolder(const std::filesystem::path& folder, const std::string& option);

/// Writes `text` to `file` (its folders created) through a temporary file beside it, renamed
/// over it once complete: a reader never sees half a file, an old file stays whole when writing
/// fails, and the temporary is removed then.
void writeTextFile(const std::filesystem::path& file, const std::string& text);

}  // namespace kautham::apps

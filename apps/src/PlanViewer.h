#pragma once

// The plan viewer: one self-contained HTML page (three.js inlined, the plan embedded as JSON)
// that animates a plan file in the browser. See docs/viewer.md.

#include <filesystem>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

namespace kautham::apps {

/// A plan that cannot be shown or a page that cannot be made; the message names the file.
class ViewError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Where Debian's libjs-three package puts three.js.
inline const std::filesystem::path kDefaultThreeDir = "/usr/share/javascript/three";

/// The three.js folder to inline: `overrideDir` when not empty, else kDefaultThreeDir. Throws
/// ViewError, telling to install libjs-three, when three.min.js or OrbitControls.js is missing.
std::filesystem::path findThreeDir(const std::string& overrideDir);

/// Checks that `plan` is a kautham plan of this format version that the page can show:
/// bodies, shapes and frames present and consistent. `source` names the plan in messages.
/// Throws ViewError.
void checkPlanForView(const nlohmann::json& plan, const std::string& source);

/// Reads and checks a plan file (checkPlanForView). Throws core::InputError naming the file
/// when it cannot be read or is not JSON (with the line where parsing stopped), ViewError naming
/// the file and the line of what is wrong when it is no viewable plan.
nlohmann::json readPlanForView(const std::filesystem::path& file);

/// The HTML page showing `plan` (checked with checkPlanForView), with three.js read from
/// `threeDir` (see findThreeDir) inlined. Throws ViewError when a library file cannot be read.
std::string planToHtml(const nlohmann::json& plan, const std::filesystem::path& threeDir);

}  // namespace kautham::apps

#include "PlanViewer.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "JsonFileText.h"
#include "PlanControlCheck.h"
#include "PlanFile.h"

namespace kautham::apps {

/// The page template, apps/src/viewer_template.html, embedded at configure time (see
/// apps/CMakeLists.txt and ViewerTemplate.cpp.in).
extern const char kViewerTemplate[];

namespace {

namespace fs = std::filesystem;

const fs::path kThreeFile = "three.min.js";
const fs::path kOrbitControlsFile = fs::path("examples") / "js" / "controls" / "OrbitControls.js";

std::string readTextFile(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw ViewError(fmt::format("cannot read '{}'", file.string()));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void replaceAll(std::string& text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos;
       at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
}

/// Replaces the one placeholder `token` of the template.
void fill(std::string& page, const std::string& token, const std::string& text) {
  const std::size_t at = page.find(token);
  if (at == std::string::npos) throw std::logic_error("viewer template lacks " + token);
  page.replace(at, token.size(), text);
}

/// Script text that cannot end its <script> element early.
std::string scriptSafe(std::string script) {
  replaceAll(script, "</script", "<\\/script");
  replaceAll(script, "</SCRIPT", "<\\/SCRIPT");
  return script;
}

/// Names the plan in messages and, when its file's text is at hand, the line of what a message
/// is about ("plan.json:64: frames[3] has no time").
class PlanSource {
 public:
  explicit PlanSource(std::string name) : name_(std::move(name)) {}
  explicit PlanSource(const JsonFileText& text) : name_(text.file().string()), text_(&text) {}

  /// An error at `line` (0: about the plan as a whole).
  [[noreturn]] void failAt(int line, const std::string& what) const {
    throw ViewError(line > 0 ? fmt::format("{}:{}: {}", name_, line, what) : name_ + ": " + what);
  }
  [[noreturn]] void fail(const std::string& what) const { failAt(0, what); }
  /// An error about `array`[`index`], named so in the message.
  [[noreturn]] void failAtElement(const std::string& array, std::size_t index,
                                  const std::string& what) const {
    failAt(text_ ? text_->elementLine(array, index) : 0,
           fmt::format("{}[{}]{}{}", array, index, what.rfind(':', 0) == 0 ? "" : " ", what));
  }
  /// The line of a key that occurs once in a plan file (0 without the text or the key).
  int keyLine(const std::string& key) const { return text_ ? text_->keyLine(key) : 0; }

 private:
  std::string name_;
  const JsonFileText* text_ = nullptr;
};

bool isPose(const nlohmann::json& pose) {
  if (!pose.is_array() || pose.size() != 7) return false;
  for (const auto& value : pose)
    if (!value.is_number()) return false;
  return true;
}

bool isPositiveNumber(const nlohmann::json& object, const char* key) {
  return object.contains(key) && object[key].is_number() && object[key].get<double>() > 0.0;
}

/// A mesh shape: "vertices" x, y, z flat, "triangles" three vertex indices each, flat.
template <typename Fail>
void checkMesh(const nlohmann::json& shape, const Fail& fail) {
  const auto& vertices = shape.contains("vertices") ? shape["vertices"] : nlohmann::json();
  const auto& triangles = shape.contains("triangles") ? shape["triangles"] : nlohmann::json();
  if (!vertices.is_array() || vertices.size() < 9 || vertices.size() % 3 != 0 ||
      !std::all_of(vertices.begin(), vertices.end(), [](const auto& v) { return v.is_number(); }))
    fail("is a mesh without \"vertices\" (x, y, z of at least three points, flat)");
  const std::size_t count = vertices.size() / 3;
  if (!triangles.is_array() || triangles.empty() || triangles.size() % 3 != 0 ||
      !std::all_of(triangles.begin(), triangles.end(), [count](const auto& i) {
        return i.is_number_integer() && i.template get<std::int64_t>() >= 0 &&
               static_cast<std::size_t>(i.template get<std::int64_t>()) < count;
      }))
    fail(fmt::format("is a mesh without \"triangles\" (three indices below {} per triangle, flat)",
                     count));
}

/// A shape of the plan's "shapes" or "visuals" (`array`), both drawn the same way.
void checkShape(const nlohmann::json& shape, const char* array, std::size_t index,
                std::size_t bodies, const PlanSource& source) {
  const auto fail = [&](const std::string& what) { source.failAtElement(array, index, what); };
  if (!shape.is_object()) fail("is not an object");
  const std::string type = shape.value("type", "");
  if (type == "box") {
    const auto& size = shape.contains("size") ? shape["size"] : nlohmann::json();
    if (!size.is_array() || size.size() != 3 || !size[0].is_number() || !size[1].is_number() ||
        !size[2].is_number())
      fail("is a box without a \"size\" of three numbers");
  } else if (type == "cylinder") {
    if (!isPositiveNumber(shape, "radius") || !isPositiveNumber(shape, "length"))
      fail("is a cylinder without a positive \"radius\" and \"length\"");
  } else if (type == "sphere") {
    if (!isPositiveNumber(shape, "radius")) fail("is a sphere without a positive \"radius\"");
  } else if (type == "mesh") {
    checkMesh(shape, fail);
  } else {
    fail(fmt::format("has type '{}'; the viewer shows box, cylinder, sphere and mesh", type));
  }
  if (!shape.contains("pose") || !isPose(shape["pose"]))
    fail("has no \"pose\" of seven numbers [x, y, z, qw, qx, qy, qz]");
  if (!shape.contains("body")) fail("has no \"body\" (an index into \"bodies\", or null)");
  const auto& body = shape["body"];
  if (!body.is_null() && !(body.is_number_integer() && body.get<std::int64_t>() >= 0 &&
                           static_cast<std::size_t>(body.get<std::int64_t>()) < bodies))
    fail(fmt::format("has \"body\" {}, not null nor an index below {}", body.dump(), bodies));
}

/// The page marks each control's frames by its "steps": the same controls validate accepts.
/// A start scene (`kautham view problem.xml`) has none.
void checkControlsForView(const nlohmann::json& plan, const PlanSource& source) {
  if (!plan.contains("controls")) return;
  const auto& controls = plan["controls"];
  if (!controls.is_array())
    source.failAt(source.keyLine("controls"), "the plan's \"controls\" is not an array");
  const auto step = plan.value("propagation_step_size", nlohmann::json());
  if (!controls.empty() && !(step.is_number() && step.get<double>() > 0.0))
    source.fail("the plan needs a positive \"propagation_step_size\"");
  for (std::size_t i = 0; i < controls.size(); ++i)
    if (const std::optional<std::string> error = planControlError(controls[i], step.get<double>()))
      source.failAtElement("controls", i, ": " + *error);
}

void checkFrames(const nlohmann::json& frames, std::size_t bodies, const PlanSource& source) {
  if (frames.empty()) source.failAt(source.keyLine("frames"), "the plan has no frames to show");
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const auto& frame = frames[i];
    if (!frame.is_object() || !frame.contains("t") || !frame["t"].is_number())
      source.failAtElement("frames", i, "has no time \"t\"");
    if (!frame.contains("poses") || !frame["poses"].is_array() || frame["poses"].size() != bodies)
      source.failAtElement("frames", i,
                           fmt::format("has no \"poses\" array of one pose per body ({})", bodies));
    for (const auto& pose : frame["poses"])
      if (!isPose(pose))
        source.failAtElement("frames", i,
                             "holds a pose that is not seven numbers [x, y, z, qw, qx, qy, qz]");
  }
}

void checkPlan(const nlohmann::json& plan, const PlanSource& source) {
  if (!plan.is_object()) source.fail("not a kautham plan (not a JSON object)");
  if (!plan.contains("format") || plan["format"] != "kautham-plan")
    source.failAt(source.keyLine("format"),
                  fmt::format("not a kautham plan (\"format\" is {}, expected \"kautham-plan\")",
                              plan.contains("format") ? plan["format"].dump() : "missing"));
  if (!plan.contains("format_version") || !plan["format_version"].is_number_integer())
    source.failAt(source.keyLine("format_version"), "the plan has no integer \"format_version\"");
  const auto version = plan["format_version"].get<std::int64_t>();
  if (version != kPlanFormatVersion)
    source.failAt(source.keyLine("format_version"),
                  fmt::format("plan format version {} is not supported; this kautham reads "
                              "version {}{}",
                              version, kPlanFormatVersion,
                              version < kPlanFormatVersion
                                  ? " (plan the problem again to get a current plan file)"
                                  : " (the file is from a newer kautham)"));
  for (const char* key : {"bodies", "shapes", "frames"})
    if (!plan.contains(key) || !plan[key].is_array())
      source.failAt(source.keyLine(key), fmt::format("the plan has no \"{}\" array", key));

  const auto& bodies = plan["bodies"];
  for (std::size_t i = 0; i < bodies.size(); ++i)
    if (!bodies[i].is_object() || !bodies[i].contains("name") || !bodies[i]["name"].is_string())
      source.failAtElement("bodies", i, "has no \"name\"");
  const auto& shapes = plan["shapes"];
  if (shapes.empty()) source.failAt(source.keyLine("shapes"), "the plan has no shapes to show");
  for (std::size_t i = 0; i < shapes.size(); ++i)
    checkShape(shapes[i], "shapes", i, bodies.size(), source);
  // Optional: what the robot looks like (plan files before visuals have none).
  if (plan.contains("visuals")) {
    const auto& visuals = plan["visuals"];
    if (!visuals.is_array())
      source.failAt(source.keyLine("visuals"), "the plan's \"visuals\" is not an array");
    for (std::size_t i = 0; i < visuals.size(); ++i)
      checkShape(visuals[i], "visuals", i, bodies.size(), source);
  }
  checkControlsForView(plan, source);
  checkFrames(plan["frames"], bodies.size(), source);
}

}  // namespace

fs::path findThreeDir(const std::string& overrideDir) {
  const fs::path dir = overrideDir.empty() ? kDefaultThreeDir : fs::path(overrideDir);
  for (const fs::path& file : {kThreeFile, kOrbitControlsFile})
    if (!fs::is_regular_file(dir / file))
      throw ViewError(fmt::format(
          "three.js not found: '{}' does not exist. Install Debian's libjs-three package "
          "(apt-get install libjs-three, or scripts/install-deps.sh), or pass --three-dir with "
          "the folder holding three.min.js and examples/js/controls/OrbitControls.js",
          (dir / file).string()));
  return dir;
}

void checkPlanForView(const nlohmann::json& plan, const std::string& source) {
  checkPlan(plan, PlanSource(source));
}

nlohmann::json readPlanForView(const fs::path& file) {
  JsonFileText text(file);
  const nlohmann::json plan = text.parse("the plan file", "not a JSON file: ");
  checkPlan(plan, PlanSource(text));
  return plan;
}

std::string planToHtml(const nlohmann::json& plan, const fs::path& threeDir) {
  // The plan sits in a <script type="application/json"> element: "</" and "<!--" may only occur
  // inside JSON strings, where "<\/" and "\u003c" mean the same and cannot close the element.
  std::string planJson = plan.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  replaceAll(planJson, "</", "<\\/");
  replaceAll(planJson, "<!--", "\\u003c!--");

  std::string page = kViewerTemplate;
  fill(page, "/*%KAUTHAM_THREE_JS%*/", scriptSafe(readTextFile(threeDir / kThreeFile)));
  fill(page, "/*%KAUTHAM_ORBIT_CONTROLS%*/",
       scriptSafe(readTextFile(threeDir / kOrbitControlsFile)));
  fill(page, "%KAUTHAM_PLAN_JSON%", planJson);
  return page;
}

}  // namespace kautham::apps

// The plan viewer in a real browser: `kautham plan --html` and `kautham view` pages opened in
// Debian's headless Chromium (a missing Chromium fails these tests: scripts/install-deps.sh
// installs it), plus malformed plan files.

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "TestPaths.h"
#include "apps/CommandTestSupport.h"

namespace kautham::apps {
namespace {

namespace fs = std::filesystem;

using test::CommandRun;
using test::kautham;
using test::readFile;
using test::run;
using test::writeFile;

/// Debian's Chromium, or "" when it is not installed.
std::string findChromium() {
  for (const char* name : {"chromium", "chromium-browser"}) {
    const CommandRun which = run(std::string("command -v ") + name + " 2>/dev/null");
    if (which.exitCode == 0 && !which.output.empty())
      return which.output.substr(0, which.output.find('\n'));
  }
  return "";
}

/// Headless Chromium on a file with a URL hash; `mode` is --dump-dom or --screenshot=FILE.
/// Returns stdout (the DOM for --dump-dom); Chromium's log goes to `folder`/chromium.log.
CommandRun chromium(const std::string& binary, const fs::path& folder, const fs::path& page,
                    const std::string& hash, const std::string& mode) {
  const fs::path profile = folder / ("profile" + std::to_string(std::rand()));
  const std::string command =
      "timeout 120 '" + binary +
      "' --headless --no-sandbox --disable-gpu --use-angle=swiftshader "
      "--enable-unsafe-swiftshader --disable-quic --no-first-run --disable-background-networking "
      "--disable-component-update --disable-sync --user-data-dir='" +
      profile.string() + "' --virtual-time-budget=5000 --window-size=1200,800 " + mode +
      " 'file://" + fs::absolute(page).string() + hash + "' 2>>'" +
      (folder / "chromium.log").string() + "'";
  return run(command);
}

/// The page text with the inlined libraries' <script> elements cut out.
std::string withoutLibraries(std::string page) {
  for (const std::string id : {"lib-three", "lib-orbitcontrols"}) {
    const std::size_t begin = page.find("<script id=\"" + id + "\">");
    const std::size_t end = page.find("</script>", begin);
    if (begin == std::string::npos || end == std::string::npos) return "missing " + id;
    page.erase(begin, end - begin);
  }
  return page;
}

/// Every external URL in the page or a fetch of one; "" when there is none. Outside the inlined
/// libraries no "http://" or "https://" may occur at all; inside them only XML namespace names
/// (never fetched) and URLs in comments (author credits, a paper cited in a shader comment).
std::string externalUrls(const std::string& page) {
  std::string found;
  for (const std::string tag : {"<script src", "<link", "<iframe", "<img", "@import", "url("})
    if (page.find(tag) != std::string::npos) found += " [" + tag + "]";
  const std::string own = withoutLibraries(page);
  for (const std::string text : {"http://", "https://", "src=", "//cdn", "fetch("})
    if (own.find(text) != std::string::npos) found += " [" + text + " outside the libraries]";
  const std::regex url("https?://[^\"'\\s)]*");
  for (auto it = std::sregex_iterator(page.begin(), page.end(), url); it != std::sregex_iterator();
       ++it) {
    const std::string address = it->str();
    if (address == "http://www.w3.org/1999/xhtml") continue;  // namespace of createElementNS
    // In a comment: "//" or a leading "*" between the line's (or string's) start and the URL.
    const std::size_t at = static_cast<std::size_t>(it->position());
    const std::size_t lineStart = page.find_last_of("\n\"", at);
    const std::string before = page.substr(lineStart + 1, at - lineStart - 1);
    const std::size_t firstChar = before.find_first_not_of(" \t");
    if (before.find("//") != std::string::npos ||
        (firstChar != std::string::npos && before[firstChar] == '*'))
      continue;
    found += " [" + address + "]";
  }
  return found;
}

class ViewCommandTest : public test::TemporaryFolderTest {
 protected:
  /// `kautham view` on a plan file holding `text`: expects exit 2, a message naming the file
  /// and containing `expected`, and no page written.
  void expectRejected(const std::string& text, const std::string& expected) {
    const fs::path plan = folder / "bad plan.json";
    const fs::path page = folder / "bad.html";
    writeFile(plan, text);
    const CommandRun view = kautham("view '" + plan.string() + "' -o '" + page.string() + "'");
    EXPECT_EQ(view.exitCode, 2) << view.output;
    EXPECT_NE(view.output.find(plan.string()), std::string::npos) << view.output;
    EXPECT_NE(view.output.find(expected), std::string::npos) << view.output;
    EXPECT_FALSE(fs::exists(page));
  }
};

TEST_F(ViewCommandTest, DefaultPlanPassesTheSelfTestInHeadlessChromium) {
  const std::string browser = findChromium();
  ASSERT_FALSE(browser.empty())
      << "Chromium is not installed; scripts/install-deps.sh installs Debian's chromium";

  const fs::path page = folder / "plan.html";
  const CommandRun plan =
      kautham("plan problems/pusher_cans_5.xml --seed 1 --html '" + page.string() + "'");
  ASSERT_EQ(plan.exitCode, 0) << plan.output;
  const std::string html = readFile(page);
  ASSERT_GT(html.size(), 100000u) << "three.js should be inlined";
  EXPECT_EQ(externalUrls(html), "");

  const CommandRun dom = chromium(browser, folder, page, "#selftest", "--dump-dom");
  ASSERT_EQ(dom.exitCode, 0) << readFile(folder / "chromium.log");
  std::smatch title;
  ASSERT_TRUE(std::regex_search(dom.output, title, std::regex("<title>([^<]*)</title>")))
      << dom.output.substr(0, 2000);
  std::smatch pass;
  const std::string verdict = title[1];
  ASSERT_TRUE(std::regex_match(
      verdict, pass,
      std::regex("SELFTEST PASS bodies=(\\d+) shapes=(\\d+) meshes=(\\d+) moved=(\\S+):([0-9.]+) "
                 "contacts=(\\d+) beliefs=(\\d+) visuals=(\\d+) visual_triangles=(\\d+)")))
      << verdict;
  EXPECT_EQ(pass[1], "9");
  EXPECT_EQ(pass[2], "10");
  EXPECT_EQ(pass[3], "0");                                  // primitives only
  EXPECT_EQ(pass[4].str().rfind("can", 0), 0u) << verdict;  // a pushed can
  EXPECT_GT(std::stod(pass[5]), 0.01) << verdict;
  EXPECT_GT(std::stoi(pass[6]), 0) << verdict;  // contact moments marked on the timeline
  EXPECT_EQ(pass[7], "0") << verdict;           // KPIECE computes no belief
  EXPECT_EQ(pass[8], "0") << verdict;           // the pusher's URDF has no <visual>

  const fs::path screenshot = folder / "plan.png";
  const CommandRun shot =
      chromium(browser, folder, page, "#frame=140", "--screenshot='" + screenshot.string() + "'");
  ASSERT_EQ(shot.exitCode, 0) << readFile(folder / "chromium.log");
  ASSERT_TRUE(fs::exists(screenshot)) << readFile(folder / "chromium.log");
  EXPECT_EQ(readFile(screenshot).substr(0, 8), "\x89PNG\r\n\x1a\n");
  EXPECT_GT(fs::file_size(screenshot), 10000u);
}

TEST_F(ViewCommandTest, MeshBodiesAreDrawnWithEveryTriangle) {
  const std::string browser = findChromium();
  ASSERT_FALSE(browser.empty()) << "Chromium is not installed";
  const fs::path planFile = folder / "plan.json";
  const fs::path page = folder / "plan.html";
  const CommandRun plan = kautham("plan tests/data/pusher_bottle.xml --seed 1 -o '" +
                                  planFile.string() + "' --html '" + page.string() + "'");
  ASSERT_EQ(plan.exitCode, 0) << plan.output;

  // The plan holds the meshes as loaded: the bottle's 290 vertices and 576 triangles.
  const nlohmann::json json = nlohmann::json::parse(readFile(planFile));
  std::size_t meshes = 0;
  for (const auto& shape : json["shapes"]) {
    if (shape["type"] != "mesh") continue;
    ++meshes;
    if (shape["owner"] == "bottle") {
      EXPECT_EQ(shape["file"], "bottle.obj");
      EXPECT_EQ(shape["vertices"].size(), 3u * 290u);
      EXPECT_EQ(shape["triangles"].size(), 3u * 576u);
    }
  }
  EXPECT_EQ(meshes, 2u);  // the bottle and the wine glass

  // The tree picture outlines each mesh seen from above: a polygon around the bottle's base.
  const fs::path svgFile = folder / "tree.svg";
  ASSERT_EQ(kautham("view '" + planFile.string() + "' --tree '" + svgFile.string() + "'").exitCode,
            0);
  const std::string svg = readFile(svgFile);
  std::smatch polygon;
  ASSERT_TRUE(std::regex_search(svg, polygon, std::regex("<polygon points=\"([^\"]*)\"")));
  std::istringstream corners(polygon[1].str());
  std::string corner;
  std::size_t count = 0;
  while (corners >> corner) {
    const double x = std::stod(corner), y = std::stod(corner.substr(corner.find(',') + 1));
    EXPECT_NEAR(std::hypot(x - 0.0, y - 0.22), 0.04, 1e-3) << corner;  // the wine glass's rim
    ++count;
  }
  EXPECT_EQ(count, 32u);  // the rim's 32 corners

  const CommandRun dom = chromium(browser, folder, page, "#selftest", "--dump-dom");
  ASSERT_EQ(dom.exitCode, 0) << readFile(folder / "chromium.log");
  std::smatch pass;
  ASSERT_TRUE(std::regex_search(
      dom.output, pass,
      std::regex("<title>SELFTEST PASS bodies=(\\d+) shapes=(\\d+) meshes=(\\d+) moved=(\\S+):")))
      << dom.output.substr(0, 2000);
  EXPECT_EQ(pass[1], "9");  // 3 robot links, the bottle, 4 cans, the wine glass
  EXPECT_EQ(pass[2], "10");
  EXPECT_EQ(pass[3], "2");  // both drawn with every triangle of the plan

  const fs::path screenshot = folder / "mesh.png";
  const CommandRun shot =
      chromium(browser, folder, page, "#frame=0", "--screenshot='" + screenshot.string() + "'");
  ASSERT_EQ(shot.exitCode, 0) << readFile(folder / "chromium.log");
  EXPECT_GT(fs::file_size(screenshot), 10000u);
}

TEST_F(ViewCommandTest, BeliefsRecordedPerControlAreShownAlongThePath) {
  const std::string browser = findChromium();
  ASSERT_FALSE(browser.empty()) << "Chromium is not installed";
  const fs::path planFile = folder / "plan.json";
  ASSERT_EQ(
      kautham("plan problems/pusher_cans_5.xml --seed 1 -o '" + planFile.string() + "'").exitCode,
      0);
  // A belief per control, as p-KPIECE records one per motion.
  nlohmann::json plan = nlohmann::json::parse(readFile(planFile));
  for (auto& control : plan["controls"]) control["belief"] = 0.8;
  writeFile(planFile, plan.dump());
  const fs::path page = folder / "plan.html";
  ASSERT_EQ(kautham("view '" + planFile.string() + "' -o '" + page.string() + "'").exitCode, 0);

  const CommandRun dom = chromium(browser, folder, page, "#selftest", "--dump-dom");
  ASSERT_EQ(dom.exitCode, 0) << readFile(folder / "chromium.log");
  std::smatch beliefs;
  ASSERT_TRUE(std::regex_search(dom.output, beliefs, std::regex("beliefs=(\\d+)"))) << dom.output;
  EXPECT_EQ(std::stoul(beliefs[1]), plan["frames"].size() - 1);  // every frame after the start
}

TEST_F(ViewCommandTest, ViewMakesTheSamePageAsPlanHtml) {
  const fs::path planFile = folder / "plan.json";
  const CommandRun plan =
      kautham("plan problems/pusher_cans_5.xml --seed 1 -o '" + planFile.string() + "' --html '" +
              (folder / "a.html").string() + "'");
  ASSERT_EQ(plan.exitCode, 0) << plan.output;
  const CommandRun view =
      kautham("view '" + planFile.string() + "' -o '" + (folder / "b.html").string() + "'");
  ASSERT_EQ(view.exitCode, 0) << view.output;
  const std::string page = readFile(folder / "b.html");
  EXPECT_EQ(page, readFile(folder / "a.html"));
  EXPECT_NE(page.find("<script type=\"application/json\" id=\"plan\">{"), std::string::npos);
  EXPECT_EQ(externalUrls(page), "");
}

TEST_F(ViewCommandTest, MalformedPlansExitTwoNamingTheFile) {
  expectRejected("this is not JSON", "bad plan.json:1: not a JSON file");
  expectRejected("", "not a JSON file");
  expectRejected(R"({"format": "something-else", "format_version": 1})", "not a kautham plan");
  expectRejected(R"({"format_version": 1, "bodies": [], "shapes": [], "frames": []})",
                 "not a kautham plan");
  expectRejected(R"({"format": "kautham-plan", "format_version": 0, "bodies": [], "shapes": [],
                     "frames": []})",
                 "plan format version 0 is not supported");
  expectRejected(R"({"format": "kautham-plan", "format_version": 2, "bodies": [], "shapes": []})",
                 "no \"frames\"");
  expectRejected(R"({"format": "kautham-plan", "format_version": 2, "bodies": [],
                     "shapes": [{"type": "box", "size": [1, 1, 1], "body": null,
                                 "pose": [0, 0, 0, 1, 0, 0, 0]}],
                     "frames": [{"t": 0, "poses": [[0, 0, 0, 1, 0, 0, 0]]}]})",
                 "one pose per body");
  expectRejected(R"({"format": "kautham-plan", "format_version": 2, "bodies": [],
                     "shapes": [{"type": "mesh", "vertices": [0, 0, 0, 1, 0, 0, 0, 1, 0],
                                 "triangles": [0, 1, 3], "body": null,
                                 "pose": [0, 0, 0, 1, 0, 0, 0]}],
                     "frames": [{"t": 0, "poses": []}]})",
                 "shapes[0] is a mesh without \"triangles\" (three indices below 3");
  expectRejected(R"({"format": "kautham-plan", "format_version": 2, "bodies": [],
                     "shapes": [{"type": "mesh", "triangles": [0, 1, 2], "body": null,
                                 "pose": [0, 0, 0, 1, 0, 0, 0]}],
                     "frames": [{"t": 0, "poses": []}]})",
                 "shapes[0] is a mesh without \"vertices\"");
}

TEST_F(ViewCommandTest, ErrorsInAPlanFileNameTheLineOfWhatIsWrong) {
  const fs::path planFile = folder / "plan.json";
  ASSERT_EQ(
      kautham("plan problems/pusher_cans_5.xml --seed 1 -o '" + planFile.string() + "'").exitCode,
      0);
  const nlohmann::json good = nlohmann::json::parse(readFile(planFile));
  ASSERT_GE(good["frames"].size(), 4u);
  ASSERT_GE(good["controls"].size(), 2u);
  // The broken element holds a key MARK, so that the test finds its line in the text itself:
  // dump(1) puts an element's '{' on the line before its first key, and capitals sort first.
  // A string holding brackets and commas in an element before must not throw the count off.
  const auto elementLine = [](const std::string& text) {
    const auto at = static_cast<std::ptrdiff_t>(text.find("\"MARK\""));
    return std::count(text.begin(), text.begin() + at, '\n');
  };
  const auto expectLine = [&](const nlohmann::json& plan, const std::string& expected) {
    const std::string text = plan.dump(1);
    writeFile(planFile, text);
    const CommandRun view =
        kautham("view '" + planFile.string() + "' -o '" + (folder / "p.html").string() + "'");
    EXPECT_EQ(view.exitCode, 2) << view.output;
    const std::string where = planFile.string() + ":" + std::to_string(elementLine(text)) + ": ";
    EXPECT_NE(view.output.find(where + expected), std::string::npos) << where << view.output;
  };
  nlohmann::json plan = good;
  plan["frames"][1]["note"] = "], [{\"t\": 1}, ";
  plan["frames"][3] = {{"MARK", 1}};
  expectLine(plan, "frames[3] has no time \"t\"");
  plan = good;
  plan["controls"][1]["MARK"] = 1;
  plan["controls"][1]["values"][0] = 7.0;
  expectLine(plan, "controls[1]: ");
  plan = good;
  plan["shapes"][2]["MARK"] = 1;
  plan["shapes"][2]["type"] = "cone";
  expectLine(plan, "shapes[2] has type 'cone'");
}

TEST_F(ViewCommandTest, TreePictureDrawsEveryTreeStateAndTheGoal) {
  const fs::path planFile = folder / "plan.json";
  const fs::path svgFile = folder / "tree.svg";
  ASSERT_EQ(
      kautham("plan problems/pusher_cans_5.xml --seed 1 -o '" + planFile.string() + "'").exitCode,
      0);
  const CommandRun view =
      kautham("view '" + planFile.string() + "' --tree '" + svgFile.string() + "'");
  ASSERT_EQ(view.exitCode, 0) << view.output;
  EXPECT_FALSE(fs::exists(folder / "plan.html"));  // only the picture was asked for

  const nlohmann::json plan = nlohmann::json::parse(std::ifstream(planFile));
  const std::size_t states = plan["statistics"]["tree_states"];
  ASSERT_EQ(plan["tree"]["end_effector"].size(), states);
  std::size_t roots = 0;
  for (const auto& parent : plan["tree"]["parent"]) roots += parent.get<int>() < 0;
  EXPECT_EQ(roots, 1u);  // one tree, grown from the start

  std::ifstream in(svgFile);
  const std::string svg((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::size_t lines = 0;
  for (std::size_t at = svg.find("<line"); at != std::string::npos; at = svg.find("<line", at + 1))
    ++lines;
  EXPECT_EQ(lines, states - roots);                            // one edge per state but the root
  EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos);  // the goal region
  EXPECT_NE(svg.find("<polyline"), std::string::npos);         // the plan's path
}

TEST_F(ViewCommandTest, TreePictureOfAPlanWithoutTreeExitsTwo) {
  const fs::path planFile = folder / "plan.json";
  ASSERT_EQ(
      kautham("plan problems/pusher_free.xml --seed 1 -o '" + planFile.string() + "'").exitCode, 0);
  nlohmann::json plan = nlohmann::json::parse(std::ifstream(planFile));
  plan.erase("tree");
  writeFile(planFile, plan.dump());
  const CommandRun view =
      kautham("view '" + planFile.string() + "' --tree '" + (folder / "t.svg").string() + "'");
  EXPECT_EQ(view.exitCode, 2) << view.output;
  EXPECT_NE(view.output.find("no search tree"), std::string::npos) << view.output;
}

TEST_F(ViewCommandTest, TreePictureOfAMalformedTreeOrGoalExitsTwoNamingTheFile) {
  // The picture read the fields unchecked: a raw json type_error, exit 1, no file named.
  const fs::path planFile = folder / "plan.json";
  ASSERT_EQ(
      kautham("plan problems/pusher_free.xml --seed 1 -o '" + planFile.string() + "'").exitCode, 0);
  const nlohmann::json plan = nlohmann::json::parse(std::ifstream(planFile));
  for (const std::string field : {"tree", "goal"}) {
    nlohmann::json edited = plan;
    edited[field] = "not an object";
    writeFile(planFile, edited.dump());
    const fs::path svgFile = folder / "t.svg";
    const CommandRun view =
        kautham("view '" + planFile.string() + "' --tree '" + svgFile.string() + "'");
    EXPECT_EQ(view.exitCode, 2) << field << ": " << view.output;
    EXPECT_NE(view.output.find(planFile.string() + ": the plan's \"tree\" or \"goal\""),
              std::string::npos)
        << view.output;
    EXPECT_FALSE(fs::exists(svgFile)) << field;
  }
}

TEST_F(ViewCommandTest, MissingPlanOrThreeJsExitsTwo) {
  const CommandRun missing = kautham("view '" + (folder / "none.json").string() + "'");
  EXPECT_EQ(missing.exitCode, 2) << missing.output;
  EXPECT_NE(missing.output.find("none.json"), std::string::npos) << missing.output;

  const CommandRun noThree =
      kautham("plan problems/pusher_cans_5.xml --html '" + (folder / "p.html").string() +
              "' --three-dir '" + (folder / "nothing").string() + "'");
  EXPECT_EQ(noThree.exitCode, 2) << noThree.output;
  EXPECT_NE(noThree.output.find("libjs-three"), std::string::npos) << noThree.output;
  EXPECT_FALSE(fs::exists(folder / "p.html"));
}

}  // namespace
}  // namespace kautham::apps

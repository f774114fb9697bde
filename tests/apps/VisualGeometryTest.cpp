// A robot's <visual> geometry in the plan file and the viewer page (issue 14): a URDF written
// here whose visual is a mesh unlike its collision box.

#include <filesystem>
#include <regex>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "apps/CommandTestSupport.h"

namespace kautham::apps {
namespace {

namespace fs = std::filesystem;
using test::CommandRun;
using test::kautham;
using test::readFile;
using test::writeFile;

using VisualGeometryTest = test::TemporaryFolderTest;

/// An octahedron of radius 5 cm: 6 corners, 8 triangles.
const char* kOctahedron =
    "v 0.05 0 0\nv -0.05 0 0\nv 0 0.05 0\nv 0 -0.05 0\nv 0 0 0.05\nv 0 0 -0.05\n"
    "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n";

/// A one-joint arm: its paddle collides as a box and looks like the octahedron (red).
const char* kArm = R"(<?xml version="1.0"?>
<robot name="looks_arm">
  <link name="base"><collision><geometry><box size="0.1 0.1 0.02"/></geometry></collision></link>
  <link name="paddle">
    <inertial><mass value="0.5"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><origin xyz="0.1 0 0"/><geometry><mesh filename="octahedron.obj"/></geometry>
      <material name="red"><color rgba="1 0 0 1"/></material></visual>
    <collision><origin xyz="0.1 0 0"/><geometry><box size="0.2 0.02 0.05"/></geometry></collision>
  </link>
  <joint name="turn" type="revolute">
    <parent link="base"/><child link="paddle"/><origin xyz="0 0 0.05"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" velocity="1" effort="10"/>
  </joint>
</robot>
)";

const char* kProblem = R"(<?xml version="1.0"?>
<Problem name="looks">
  <Robot robot="looks_arm.urdf" scale="1"><Home X="0" Y="0" Z="0.05"/></Robot>
  <Planner>
    <Parameters><Name>KPIECE</Name></Parameters>
    <Queries><Query><Init>0.5</Init><Goal>1.0</Goal></Query></Queries>
  </Planner>
</Problem>
)";

/// The plan JSON embedded in a viewer page.
nlohmann::json embeddedPlan(const std::string& page) {
  const std::string open = "<script type=\"application/json\" id=\"plan\">";
  const std::size_t begin = page.find(open) + open.size();
  std::string text = page.substr(begin, page.find("</script>", begin) - begin);
  for (std::size_t at = text.find("<\\/"); at != std::string::npos; at = text.find("<\\/", at))
    text.replace(at, 3, "</");
  return nlohmann::json::parse(text);
}

TEST_F(VisualGeometryTest, TheStartPageCarriesTheVisualMeshBesideTheCollisionBox) {
  writeFile(folder / "octahedron.obj", kOctahedron);
  writeFile(folder / "looks_arm.urdf", kArm);
  writeFile(folder / "looks.xml", kProblem);
  const fs::path page = folder / "looks.html";
  const CommandRun view =
      kautham("view '" + (folder / "looks.xml").string() + "' -o '" + page.string() + "'");
  ASSERT_EQ(view.exitCode, 0) << view.output;
  const nlohmann::json plan = embeddedPlan(readFile(page));

  // The physics' shapes are unchanged: two boxes.
  ASSERT_EQ(plan["shapes"].size(), 2u);
  for (const auto& shape : plan["shapes"]) EXPECT_EQ(shape["type"], "box");
  // The visuals: the base (no <visual>) by its collision box, the paddle by its octahedron.
  ASSERT_EQ(plan["visuals"].size(), 2u) << plan["visuals"].dump();
  const nlohmann::json& base = plan["visuals"][0];
  EXPECT_EQ(base["link"], "base");
  EXPECT_EQ(base["type"], "box");
  EXPECT_TRUE(base["body"].is_null());
  const nlohmann::json& paddle = plan["visuals"][1];
  EXPECT_EQ(paddle["link"], "paddle");
  EXPECT_EQ(paddle["type"], "mesh");
  EXPECT_EQ(paddle["file"], "octahedron.obj");
  EXPECT_EQ(paddle["vertices"].size(), 18u);
  EXPECT_EQ(paddle["triangles"].size(), 24u);
  EXPECT_EQ(paddle["colour"], nlohmann::json({1.0, 0.0, 0.0, 1.0}));
  // On the paddle's body, where its collision box is: the same pose in the body frame.
  ASSERT_FALSE(paddle["body"].is_null());
  const nlohmann::json& box = plan["shapes"][1];
  EXPECT_EQ(paddle["body"], box["body"]);
  for (int k = 0; k < 7; ++k)
    EXPECT_NEAR(paddle["pose"][k].get<double>(), box["pose"][k].get<double>(), 1e-9) << k;
}

TEST_F(VisualGeometryTest, ThePageDrawsTheVisualsAndSwapsInTheCollisionShapes) {
  writeFile(folder / "octahedron.obj", kOctahedron);
  writeFile(folder / "looks_arm.urdf", kArm);
  writeFile(folder / "looks.xml", kProblem);
  const fs::path page = folder / "looks.html";
  ASSERT_EQ(
      kautham("view '" + (folder / "looks.xml").string() + "' -o '" + page.string() + "'").exitCode,
      0);
  const CommandRun dom = test::run(
      "timeout 120 chromium --headless --no-sandbox --disable-gpu --use-angle=swiftshader "
      "--enable-unsafe-swiftshader --disable-quic --no-first-run --disable-background-networking "
      "--disable-component-update --disable-sync --user-data-dir='" +
      (folder / "profile").string() +
      "' --virtual-time-budget=5000 --window-size=1200,800 --dump-dom 'file://" +
      fs::absolute(page).string() + "#selftest' 2>/dev/null");
  std::smatch title;
  ASSERT_TRUE(std::regex_search(dom.output, title, std::regex("<title>([^<]*)</title>")))
      << dom.output.substr(0, 500);
  const std::string verdict = title[1];
  EXPECT_EQ(verdict.rfind("SELFTEST PASS", 0), 0u) << verdict;
  EXPECT_NE(verdict.find(" visuals=2 visual_triangles=8"), std::string::npos) << verdict;
}

TEST_F(VisualGeometryTest, AMissingVisualMeshCostsAWarningAndTheLinkShowsItsCollisionBox) {
  std::string arm = kArm;
  arm.replace(arm.find("octahedron.obj"), 14, "missing.obj");
  writeFile(folder / "looks_arm.urdf", arm);
  writeFile(folder / "looks.xml", kProblem);
  const fs::path page = folder / "looks.html";
  const CommandRun view =
      kautham("view '" + (folder / "looks.xml").string() + "' -o '" + page.string() + "'");
  ASSERT_EQ(view.exitCode, 0) << view.output;
  EXPECT_NE(view.output.find("looks_arm.urdf:6: link 'paddle': visual mesh 'missing.obj': file "
                             "not found"),
            std::string::npos)
      << view.output;
  const nlohmann::json plan = embeddedPlan(readFile(page));
  // No link keeps a visual, so the page draws the robot by its collision shapes alone.
  EXPECT_TRUE(plan["visuals"].empty()) << plan["visuals"].dump();
}

}  // namespace
}  // namespace kautham::apps

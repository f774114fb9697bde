// The `kautham` program on a problem with mesh objects (tests/data/pusher_bottle.xml).

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "TestPaths.h"
#include "apps/CommandTestSupport.h"

namespace kautham::apps {
namespace {

namespace fs = std::filesystem;

using test::CommandRun;
using test::kautham;

using MeshCommandTest = test::TemporaryFolderTest;

TEST_F(MeshCommandTest, CheckAcceptsTheBottleProblemAndDescribesItsMeshes) {
  const CommandRun run = kautham("check tests/data/pusher_bottle.xml");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("target: wine_glass"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("bottle (bottle.obj: 290 vertices, 576 triangles; collides as its "
                            "convex hull of"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("wine_glass (wine_glass.stl: 386 vertices, 768 triangles"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("start valid"), std::string::npos) << run.output;
}

TEST_F(MeshCommandTest, PlanSolvesTheBottleProblemByPushingTheBottle) {
  const fs::path planFile = folder / "plan.json";
  const CommandRun run =
      kautham("plan tests/data/pusher_bottle.xml --seed 1 -o '" + planFile.string() + "'");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("solved    yes"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("reaches the goal"), std::string::npos) << run.output;
  std::ifstream in(planFile);
  const nlohmann::json plan = nlohmann::json::parse(in);
  EXPECT_EQ(plan["result"]["replay"]["violation"], "none");
  bool bottleMoved = false;
  for (const auto& moved : plan["result"]["replay"]["moved_objects"])
    bottleMoved |= moved["name"] == "bottle" && moved["distance"].get<double>() > 0.01;
  EXPECT_TRUE(bottleMoved) << plan["result"]["replay"].dump();  // it stood where the goal is
}

}  // namespace
}  // namespace kautham::apps

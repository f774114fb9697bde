// Sensed environments: octree files (.bt and .ot) turned into the boxes of a fixed object, on
// the shipped shelf, on octrees written here, and on damaged copies of the shelf's file.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <octomap/ColorOcTree.h>
#include <octomap/OcTree.h>
#include <unistd.h>

#include "TestPaths.h"
#include "kautham/core/OctomapEnvironment.h"
#include "kautham/core/ProblemLoader.h"

namespace kautham::core {
namespace {

namespace fs = std::filesystem;
using test::repoFile;

const SourceLocation kWhere{"scene.xml", 7};

double overlapVolume(const Eigen::AlignedBox3d& a, const Eigen::AlignedBox3d& b) {
  double volume = 1.0;
  for (int i = 0; i < 3; ++i)
    volume *= std::max(0.0, std::min(a.max()[i], b.max()[i]) - std::max(a.min()[i], b.min()[i]));
  return volume;
}

int boxesContaining(const OctomapBoxes& boxes, const Eigen::Vector3d& point) {
  return static_cast<int>(std::count_if(boxes.boxes.begin(), boxes.boxes.end(),
                                        [&](const auto& box) { return box.contains(point); }));
}

std::string readBytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// A temporary folder of the test's own.
class OctreeFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    folder_ = fs::temp_directory_path() / ("kautham_octomap_tests_" + std::string(info->name()) +
                                           "_" + std::to_string(::getpid()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(folder_, ignored);
  }
  fs::path folder_;
};

// ----- the shipped shelf -----

TEST(ShippedShelf, BoxesCoverExactlyTheOccupiedLeaves) {
  const fs::path file = repoFile("models/environments/shelf.bt");
  const OctomapBoxes boxes = readOctomapBoxes(file, kDefaultOccupancyThreshold, kWhere);
  EXPECT_DOUBLE_EQ(boxes.resolution, 0.02);

  // The same file read by octomap directly: every occupied leaf lies in exactly one box.
  octomap::OcTree tree(0.1);
  ASSERT_TRUE(tree.readBinary(file.string()));
  std::size_t leaves = 0;
  double leafVolume = 0.0;
  for (auto it = tree.begin_leafs(); it != tree.end_leafs(); ++it) {
    if (!tree.isNodeOccupied(*it)) continue;
    ++leaves;
    leafVolume += std::pow(it.getSize(), 3);
    const octomap::point3d c = it.getCoordinate();
    ASSERT_EQ(boxesContaining(boxes, Eigen::Vector3d(c.x(), c.y(), c.z())), 1) << "leaf at " << c;
  }
  EXPECT_EQ(boxes.leaves, leaves);
  EXPECT_GT(leaves, 1000u);
  EXPECT_LT(boxes.boxes.size(), leaves / 100);  // merging does work

  // The boxes do not overlap, and their volume is the leaves' volume: their union is exactly
  // the occupied space. The shelf (two uprights 4 x 30 x 160 cm, three boards 92 x 30 x 2 cm).
  double boxVolume = 0.0;
  for (std::size_t i = 0; i < boxes.boxes.size(); ++i) {
    boxVolume += boxes.boxes[i].volume();
    for (std::size_t j = i + 1; j < boxes.boxes.size(); ++j)
      EXPECT_EQ(overlapVolume(boxes.boxes[i], boxes.boxes[j]), 0.0) << i << " " << j;
  }
  const double shelf = 2 * 0.04 * 0.30 * 1.6 + 3 * 0.92 * 0.30 * 0.02;
  EXPECT_NEAR(boxVolume, leafVolume, 1e-9);
  EXPECT_NEAR(boxes.occupiedVolume, leafVolume, 1e-9);
  EXPECT_NEAR(boxVolume, shelf, 1e-6);

  EXPECT_EQ(boxesContaining(boxes, {-0.48, 0.5, 1.3}), 1);  // left upright
  EXPECT_EQ(boxesContaining(boxes, {0.49, 0.7, 0.1}), 1);   // right upright, near the floor
  EXPECT_EQ(boxesContaining(boxes, {0.0, 0.43, 0.77}), 1);  // lowest board, front edge
  EXPECT_EQ(boxesContaining(boxes, {0.0, 0.5, 1.59}), 1);   // top board
  EXPECT_EQ(boxesContaining(boxes, {0.0, 0.5, 0.95}), 0);   // between the boards
  EXPECT_EQ(boxesContaining(boxes, {0.0, 0.41, 0.77}), 0);  // just in front of the shelf
  EXPECT_EQ(boxesContaining(boxes, {0.0, 0.5, 0.75}), 0);   // just under the lowest board
}

TEST(ShippedShelf, DamagedCopiesAreRejectedOrLoadedButNeverCrash) {
  const std::string bytes = readBytes(repoFile("models/environments/shelf.bt"));
  const fs::path folder =
      fs::temp_directory_path() / ("kautham_octomap_damaged_" + std::to_string(::getpid()));
  fs::create_directories(folder);
  const fs::path file = folder / "damaged.bt";
  int rejected = 0;
  int loaded = 0;
  auto tryLoad = [&](const std::string& content) {
    std::ofstream(file, std::ios::binary) << content;
    try {
      const OctomapBoxes boxes = readOctomapBoxes(file, kDefaultOccupancyThreshold, kWhere);
      EXPECT_FALSE(boxes.boxes.empty());
      ++loaded;
    } catch (const InputError& error) {
      EXPECT_EQ(error.where().line, 7) << error.what();
      ++rejected;
    }
  };
  for (std::size_t length = 0; length < bytes.size(); length += 13)
    tryLoad(bytes.substr(0, length));  // truncated
  for (std::size_t at = 0; at < bytes.size(); at += 17) {
    std::string flipped = bytes;
    flipped[at] = static_cast<char>(flipped[at] ^ 0x5a);
    tryLoad(flipped);
  }
  fs::remove_all(folder);
  EXPECT_GT(rejected, 300);  // every truncation is; most flips are
  EXPECT_GT(loaded, 0);      // a flipped occupancy code still makes a tree
}

// ----- octrees written here -----

TEST_F(OctreeFiles, AFullOtFileIsReadAndTheThresholdDecidesWhatIsOccupied) {
  octomap::OcTree tree(0.05);
  for (int i = 0; i < 3; ++i)  // a row of three sure voxels: probability 0.88
    tree.setNodeValue(octomap::point3d(0.025f + 0.05f * i, 0.025f, 0.025f), 2.0f);
  tree.setNodeValue(octomap::point3d(0.525f, 0.025f, 0.025f), 0.5f);   // probability 0.62
  tree.setNodeValue(octomap::point3d(0.025f, 0.525f, 0.025f), -2.0f);  // free
  const fs::path file = folder_ / "scene.ot";
  ASSERT_TRUE(tree.write(file.string()));

  const OctomapBoxes loose = readOctomapBoxes(file, 0.5, kWhere);
  EXPECT_EQ(loose.leaves, 4u);
  EXPECT_EQ(loose.boxes.size(), 2u);  // the row is one box
  EXPECT_EQ(boxesContaining(loose, {0.53, 0.03, 0.03}), 1);

  const OctomapBoxes strict = readOctomapBoxes(file, 0.7, kWhere);
  EXPECT_EQ(strict.leaves, 3u);
  ASSERT_EQ(strict.boxes.size(), 1u);
  EXPECT_TRUE(strict.boxes[0].min().isApprox(Eigen::Vector3d(0, 0, 0), 1e-12));
  EXPECT_TRUE(strict.boxes[0].max().isApprox(Eigen::Vector3d(0.15, 0.05, 0.05), 1e-12))
      << strict.boxes[0].max().transpose();
}

TEST_F(OctreeFiles, AnOtFileOfAnotherTreeTypeIsRejected) {
  octomap::ColorOcTree tree(0.05);
  tree.updateNode(octomap::point3d(0.1f, 0.1f, 0.1f), true);
  const fs::path file = folder_ / "colour.ot";
  ASSERT_TRUE(tree.write(file.string()));
  try {
    readOctomapBoxes(file, 0.5, kWhere);
    FAIL() << "loaded";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()).rfind("scene.xml:7: ", 0), 0u) << error.what();
    EXPECT_NE(std::string(error.what()).find("holds a 'ColorOcTree' tree; only an OcTree"),
              std::string::npos)
        << error.what();
  }
}

TEST_F(OctreeFiles, OtherExtensionsAreRejected) {
  const fs::path file = folder_ / "scene.pcd";
  std::ofstream(file) << "points";
  EXPECT_THROW(readOctomapBoxes(file, 0.5, kWhere), InputError);
}

TEST(EnvironmentObject, IsOneFixedLinkCarryingEveryBox) {
  OctomapBoxes boxes;
  boxes.resolution = 0.1;
  boxes.leaves = 3;
  boxes.boxes = {{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.2, 0.1, 0.1)},
                 {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(1.1, 0.1, 0.1)}};
  const Pose home = Pose::fromAxisAngle({0, 0, 1}, {0, 0, 1}, 0.0);
  const ObjectInstance object = makeEnvironmentObject("scene", "scene.bt", boxes, home, kWhere);
  EXPECT_EQ(object.role, ObjectRole::Fixed);
  ASSERT_TRUE(object.environment);
  EXPECT_EQ(object.environment->boxes, 2u);
  EXPECT_EQ(object.environment->leaves, 3u);
  ASSERT_EQ(object.model.links.size(), 1u);
  EXPECT_EQ(object.model.links[0].collisions.size(), 2u);
  EXPECT_TRUE(object.model.movableJoints().empty());
  const Eigen::AlignedBox3d bounds = boundsAtHome(object);
  EXPECT_TRUE(bounds.min().isApprox(Eigen::Vector3d(0, 0, 1)));
  EXPECT_TRUE(bounds.max().isApprox(Eigen::Vector3d(1.1, 0.1, 1.1)));
}

// ----- problems with an <Environment> -----

TEST(EnvironmentProblem, PusherShelfHasTheShelfAsAFixedObject) {
  const Problem problem = loadProblem(repoFile("problems/pusher_shelf.xml"));
  const auto shelf = problem.findObject("shelf");
  ASSERT_TRUE(shelf);
  const ObjectInstance& object = problem.objects[*shelf];
  EXPECT_EQ(object.role, ObjectRole::Fixed);
  ASSERT_TRUE(object.environment);
  EXPECT_EQ(object.environment->octree,
            fs::weakly_canonical(repoFile("models/environments/shelf.bt")));
  EXPECT_EQ(object.model.links[0].collisions.size(), object.environment->boxes);
  EXPECT_EQ(object.where.line, 17);
  const Eigen::AlignedBox3d bounds = boundsAtHome(object);
  EXPECT_TRUE(bounds.min().isApprox(Eigen::Vector3d(-0.5, 0.42, 0.0), 1e-9));
  EXPECT_TRUE(bounds.max().isApprox(Eigen::Vector3d(0.5, 0.72, 1.6), 1e-9));
  EXPECT_EQ(problem.objects[*problem.supportObject()].name, "table");
}

TEST_F(OctreeFiles, HomeMovesTheEnvironmentAndTheNameDefaults) {
  std::string text = readBytes(repoFile("problems/pusher_shelf.xml"));
  const std::string from = "<Environment octomap=\"environments/shelf.bt\" name=\"shelf\"/>";
  const auto at = text.find(from);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, from.size(),
               "<Environment octomap=\"environments/shelf.bt\"><Home X=\"0\" Y=\"0.1\" "
               "Z=\"0\"/></Environment>");
  const fs::path file = folder_ / "moved.xml";
  std::ofstream(file) << text;
  const Problem problem = loadProblem(file, {repoFile("models")});
  const auto environment = problem.findObject("environment");
  ASSERT_TRUE(environment);
  const Eigen::AlignedBox3d bounds = boundsAtHome(problem.objects[*environment]);
  EXPECT_TRUE(bounds.min().isApprox(Eigen::Vector3d(-0.5, 0.52, 0.0), 1e-9));
}

}  // namespace
}  // namespace kautham::core

// Writes the example sensed environment, models/environments/shelf.bt: a shelf standing on the
// floor behind the table of the pusher problems, as an OctoMap octree with 2 cm voxels.
//
//   build/apps/make_shelf_octomap [OUTPUT.bt]     (default: models/environments/shelf.bt)
//
// The table top spans x in [-0.6, 0.6], y in [-0.4, 0.4] at z = 0.75 (see
// problems/pusher_cans_5.xml). The shelf is 1 m wide (x in [-0.5, 0.5]), 30 cm deep
// (y in [0.42, 0.72], 2 cm behind the table) and 1.6 m tall: two uprights 4 cm thick from the
// floor to the top, and three boards 2 cm thick between them. The lowest board, at
// z in [0.76, 0.78], is at the height of the pusher's palm (z in [0.755, 0.795]), so the
// fingers can touch it when the gripper reaches over the back edge of the table. Every face
// lies on the 2 cm voxel grid, so the voxels fill the shelf exactly.

#include <cmath>
#include <cstdio>
#include <string>

#include <octomap/OcTree.h>

namespace {

constexpr double kVoxel = 0.02;

/// Marks every voxel whose centre lies inside [min, max] (metres) as occupied.
void fill(octomap::OcTree& tree, double x0, double x1, double y0, double y1, double z0, double z1) {
  // Voxel i spans [i * kVoxel, (i + 1) * kVoxel]: round the faces to whole voxels.
  const auto first = [](double v) { return static_cast<int>(std::lround(v / kVoxel)); };
  for (int i = first(x0); i < first(x1); ++i)
    for (int j = first(y0); j < first(y1); ++j)
      for (int k = first(z0); k < first(z1); ++k)
        tree.updateNode(octomap::point3d(static_cast<float>((i + 0.5) * kVoxel),
                                         static_cast<float>((j + 0.5) * kVoxel),
                                         static_cast<float>((k + 0.5) * kVoxel)),
                        true);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string output = argc > 1 ? argv[1] : "models/environments/shelf.bt";
  if (argc > 2 || output == "-h" || output == "--help") {
    std::fprintf(stderr, "usage: %s [OUTPUT.bt]\n", argv[0]);
    return 2;
  }
  octomap::OcTree tree(kVoxel);
  constexpr double kLeft = -0.5, kRight = 0.5, kFront = 0.42, kBack = 0.72;
  constexpr double kUpright = 0.04, kBoard = 0.02, kTop = 1.6;
  fill(tree, kLeft, kLeft + kUpright, kFront, kBack, 0.0, kTop);    // left upright
  fill(tree, kRight - kUpright, kRight, kFront, kBack, 0.0, kTop);  // right upright
  for (double z : {0.76, 1.16, kTop - kBoard})                      // boards
    fill(tree, kLeft + kUpright, kRight - kUpright, kFront, kBack, z, z + kBoard);
  tree.updateInnerOccupancy();
  if (!tree.writeBinary(output)) {
    std::fprintf(stderr, "cannot write %s\n", output.c_str());
    return 1;
  }
  std::printf("wrote %s: %zu occupied leaves, %zu nodes, %g m voxels\n", output.c_str(),
              tree.getNumLeafNodes(), tree.size(), tree.getResolution());
  return 0;
}

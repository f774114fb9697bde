#pragma once

// The dense-clutter suite of `kautham generate clutter` (the default layout, "side"): the
// paper's problem. A robot must bring its open gripper to a side pre-grasp of a target at the
// back of a fixed zone of the table, which N movable objects fill at random, so the clutter
// grows with N; from 10 objects on, ceil(N/5) of them stand on the pre-grasp or in the straight
// corridor of the approach. See docs/scenes.md.

#include <cstdint>
#include <string>
#include <vector>

#include "ClutterGenerator.h"

namespace kautham::apps {

/// One movable object of a side-grasp scene, in multiples of 0.1 mm.
struct SceneObject {
  std::string kind;  ///< "can", "box" or "bottle"
  std::int64_t x = 0;
  std::int64_t y = 0;
  bool blocker = false;  ///< its footprint crosses the approach corridor or the free space
};

/// How many objects must block the approach in a scene of `objects` objects.
int requiredBlockers(int objects);
/// The most objects whose requiredBlockers() is at most `blockers`: what to ask for when only
/// that many blockers fit.
int mostObjectsForBlockers(int blockers);

/// Places the objects of a side-grasp scene. Throws std::invalid_argument for options out of
/// range and when not all objects fit (the message says how many did).
std::vector<SceneObject> placeSideGraspClutter(const ClutterOptions& options);

/// The whole problem file of a side-grasp scene.
std::string sideGraspProblemXml(const ClutterOptions& options,
                                const std::vector<SceneObject>& objects,
                                const std::string& problemName, const std::string& commandLine);

}  // namespace kautham::apps

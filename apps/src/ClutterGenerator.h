#pragma once

// Cluttered table scenes for `kautham generate clutter`: a robot at the side of the table, a
// target glass, and N movable cans placed at random (reproducibly, from a seed) between the
// robot and the target and around the target. See docs/scenes.md.

#include <cstdint>
#include <string>
#include <vector>

namespace kautham::apps {

struct ClutterOptions {
  std::string robot = "kuka";  ///< one of clutterRobots()
  int objects = 5;             ///< movable cans, 0 ... kMaxClutterObjects
  std::uint64_t seed = 1;
  std::string target = "glass";
  double gap = 0.01;  ///< least distance between any two objects (m)
  /// "side": the dense suite, a side pre-grasp (SideGraspClutter.h); "top": the earlier
  /// top-down suite (kuka_cans_N), kept for the regression tests that use it.
  std::string layout = "side";
  bool mix = false;  ///< side layout: a bottle, boxes and cans instead of cans only
};

constexpr int kMaxClutterObjects = 60;

/// A can's place on the table, in multiples of 0.1 mm so that what is checked is exactly what
/// is written.
struct CanPlacement {
  std::int64_t x = 0;    ///< 1e-4 m
  std::int64_t y = 0;    ///< 1e-4 m
  bool blocker = false;  ///< placed on purpose on the approach to the goal
};

/// The robots the generator knows, by their command-line names.
std::vector<std::string> clutterRobots();

/// Places the cans. Throws std::invalid_argument for options out of range and when not all
/// cans fit (the message says how many did).
std::vector<CanPlacement> placeClutter(const ClutterOptions& options);

/// The whole problem file. `problemName` goes into <Problem name>, `commandLine` into the
/// header comment (it must not contain "--", which XML comments do not allow).
std::string clutterProblemXml(const ClutterOptions& options, const std::vector<CanPlacement>& cans,
                              const std::string& problemName, const std::string& commandLine);

/// The command that regenerates a scene, with short options only (XML comments may not
/// contain "--"): `kautham generate clutter -r kuka -n 10 -s 3 -o FILE`.
std::string clutterCommandLine(const ClutterOptions& options, const std::string& outputName);

}  // namespace kautham::apps

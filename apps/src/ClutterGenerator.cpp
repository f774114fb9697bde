#include "ClutterGenerator.h"
#include "PlacementMath.h"

#include <algorithm>
#include <random>
#include <stdexcept>

#include <fmt/format.h>

namespace kautham::apps {

namespace {

using namespace placement;

constexpr Units kTableHalfX = 6000;  // models/objects/table.urdf: 1.2 m x 0.8 m, centre (0, 0)
constexpr Units kTableHalfY = 4000;
constexpr Units kTableMargin = 200;        // a can's edge stays 2 cm inside the table's edge
constexpr Units kCanRadius = 330;          // models/objects/can.urdf
constexpr Units kGlassRadius = 400;        // models/objects/glass.urdf
constexpr Units kRobotClearance = 200;     // a can's edge stays 2 cm from the robot's footprint
constexpr Units kGoalClearance = 500;      // fewer than 10 cans: 5 cm between a can and the goal
constexpr Units kOnGoalRadius = 200;       // the first blocker's centre: within 2 cm of the goal
constexpr Units kNearGoalRadius = 1000;    // further blockers: within 10 cm of the goal
constexpr int kBlockersFrom = 10;          // from this many cans on, some block the approach
constexpr int kMaxBlockers = 3;            // one per 10 cans, at most this many
constexpr Units kGrowStep = 500;           // the clutter region grows by 5 cm when crowded
constexpr Units kMaxRegion = 14000;        // by then it covers the whole table
constexpr int kAttemptsPerRegion = 400;    // failed samples before the region grows
constexpr int kAttemptsAtLargest = 20000;  // failed samples at full size before giving up

/// An axis-aligned rectangle of the table that a can must keep clear of: the footprint of
/// a part of the robot that is less than 15 cm above the cans' tops at the start (measured
/// with the URDF's kinematics; tests/apps/GenerateCommandTest.cpp checks it).
struct KeepOut {
  Units xmin, xmax, ymin, ymax;
};

/// Everything the generator needs to know about one robot. The base pose, <Init>, goal link
/// and workspace are those of tests/data/kuka_table.xml and tests/data/yumi_table.xml.
struct RobotSetup {
  const char* key;
  const char* description;
  const char* urdf;
  const char* name;
  const char* homeComment;
  const char* home;
  const char* controls;  ///< the Kautham control set: arm joints only, fingers held open
  const char* init;
  const char* initComment;
  const char* goalLink;
  Point target;       ///< the glass's centre
  Units goalOffsetY;  ///< the pre-grasp point: this far from the glass, towards the robot
  const char* workspaceMin;
  const char* workspaceMax;
  Units corridorStartY;  ///< the corridor's end on the robot's side (its arm's shadow)
  std::vector<KeepOut> keepOuts;
};

const std::vector<RobotSetup>& robotSetups() {
  static const std::vector<RobotSetup> setups = {
      {"kuka",
       "A KUKA LWR 4+ with a two-finger gripper stands at the side of the table (base level with\n"
       "     the table top, on a stand just outside its edge) and must bring its TCP to a "
       "pre-grasp\n"
       "     point in front of a glass. The arm starts bent over the table, the gripper "
       "pointing down.",
       "robots/kuka_lwr4.urdf",
       "kuka",
       "turned +90 deg about z: the arm's +x (where A2 tips it for positive angles) faces the "
       "table",
       R"(X="0.0" Y="-0.5" Z="0.75" WX="0" WY="0" WZ="1" TH="1.5707963")",
       "robots/controls/kuka_lwr4_arm.cntr",
       "0.5 0.6667 0.5 0.125 0.5 0.7083 0.5",
       "normalized A1..A7 (the control set holds the fingers half open, a 4.5 cm gap).\n"
       "             A2 = +40 deg, A4 = -90 deg, A6 = +50 deg: the gripper points straight down.",
       "kuka_tcp",
       {0, 2800},
       1200,
       "-0.5 -0.35 0.77",
       "0.5 0.38 1.2",
       -4000,
       // the base (just off the table) and the shoulder (link 2, 15 cm above the cans), and
       // the palm and fingers, 7.6 cm above the cans
       {{-800, 800, -5800, -3220}, {-600, 600, 310, 810}}},
      {"yumi",
       "An ABB YuMi stands on the table, facing +y, and must bring its left TCP to a pre-grasp\n"
       "     point in front of a glass. Both grippers start pointing down, fingertips about 11 cm\n"
       "     above the cans' tops.",
       "robots/yumi.urdf",
       "yumi",
       "turned +90 deg about z: YuMi's front (+x of yumi_body) faces +y; the base plate rests\n"
       "         on the table top (robot bases do not collide with fixed obstacles)",
       R"(X="0.0" Y="-0.3" Z="0.75" WX="0" WY="0" WZ="1" TH="1.5707963")",
       "robots/controls/yumi_left_arm.cntr",
       "0.5737 0.6029 0.5178 0.9737 0.7142 0.5029 0.5",
       "normalized left arm axes 1, 2, 7, 3, 4, 5, 6 (the control set holds the right arm\n"
       "             folded away and every finger half open, a 2.5 cm gap)",
       "yumi_left_tcp",
       {-1200, 2000},
       1000,
       "-0.5 -0.1 0.77",
       "0.5 0.38 1.2",
       -1000,
       // the base plate, and both grippers, 11 cm above the cans
       {{-2500, 2500, -5000, -1000}, {-1640, -760, -520, 110}, {2690, 3310, -930, -60}}},
  };
  return setups;
}

const RobotSetup& findSetup(const std::string& robot) {
  for (const RobotSetup& setup : robotSetups())
    if (robot == setup.key) return setup;
  throw std::invalid_argument(
      fmt::format("unknown robot '{}'; expected {}", robot, fmt::join(clutterRobots(), " or ")));
}

Point goalPoint(const RobotSetup& setup) {
  return {setup.target.x, setup.target.y - setup.goalOffsetY};
}

/// Squared distance from a point to a rectangle (0 inside it).
Units distanceSquared(Point p, const KeepOut& box) {
  const Units dx = std::max<Units>({box.xmin - p.x, 0, p.x - box.xmax});
  const Units dy = std::max<Units>({box.ymin - p.y, 0, p.y - box.ymax});
  return squared(dx) + squared(dy);
}

class Placer {
 public:
  Placer(const RobotSetup& setup, const ClutterOptions& options)
      : setup_(setup),
        gap_(static_cast<Units>(options.gap / kUnit + 0.5)),
        keepGoalClear_(options.objects < kBlockersFrom) {}

  /// Whether a can may stand at `p`, given the cans placed so far.
  bool fits(Point p, bool onPurposeNearGoal) const {
    constexpr Units kLimitX = kTableHalfX - kTableMargin - kCanRadius;
    constexpr Units kLimitY = kTableHalfY - kTableMargin - kCanRadius;
    if (p.x < -kLimitX || p.x > kLimitX || p.y < -kLimitY || p.y > kLimitY) return false;
    if (distanceSquared(p, setup_.target) < squared(kCanRadius + kGlassRadius + gap_)) return false;
    for (const KeepOut& box : setup_.keepOuts)
      if (distanceSquared(p, box) < squared(kCanRadius + kRobotClearance)) return false;
    if (keepGoalClear_ && !onPurposeNearGoal &&
        distanceSquared(p, goalPoint(setup_)) < squared(kCanRadius + kGoalClearance))
      return false;
    for (const CanPlacement& can : cans_)
      if (distanceSquared(p, Point{can.x, can.y}) < squared(2 * kCanRadius + gap_)) return false;
    return true;
  }

  /// Tries to put a can in the disc about the goal; false if it does not fit there.
  bool placeNearGoal(std::mt19937_64& random, Units radius) {
    for (int attempt = 0; attempt < kAttemptsPerRegion; ++attempt) {
      const Point p = inDisc(random, goalPoint(setup_), radius);
      if (fits(p, true)) {
        cans_.push_back({p.x, p.y, true});
        return true;
      }
    }
    return false;
  }

  /// Puts a can in the clutter region: most samples in a disc about the target and the goal in
  /// front of it, the others in the corridor from the robot's side of the table to the goal. The
  /// region starts small and grows each time it seems full; false when even the whole table has no
  /// room.
  bool placeInClutter(std::mt19937_64& random) {
    int failures = 0;
    for (;;) {
      const Point p = sampleClutter(random);
      if (fits(p, false)) {
        cans_.push_back({p.x, p.y, false});
        return true;
      }
      ++failures;
      if (region_ < kMaxRegion && failures >= kAttemptsPerRegion) {
        region_ = std::min(region_ + kGrowStep, kMaxRegion);
        failures = 0;
      } else if (region_ >= kMaxRegion && failures >= kAttemptsAtLargest) {
        return false;
      }
    }
  }

  void startRegion(int objects) { region_ = 1500 + 100 * static_cast<Units>(objects); }

  const std::vector<CanPlacement>& cans() const { return cans_; }

 private:
  Point sampleClutter(std::mt19937_64& random) const {
    const Point goal = goalPoint(setup_);
    const Point centre{(goal.x + setup_.target.x) / 2, (goal.y + setup_.target.y) / 2};
    if (uniform(random, 0, 99) < 60) return inDisc(random, centre, region_);
    return {uniform(random, goal.x - region_ / 2, goal.x + region_ / 2),
            uniform(random, setup_.corridorStartY, goal.y)};
  }

  const RobotSetup& setup_;
  Units gap_;
  bool keepGoalClear_;
  Units region_ = 0;
  std::vector<CanPlacement> cans_;
};

}  // namespace

std::vector<std::string> clutterRobots() {
  std::vector<std::string> names;
  for (const RobotSetup& setup : robotSetups()) names.emplace_back(setup.key);
  return names;
}

std::vector<CanPlacement> placeClutter(const ClutterOptions& options) {
  const RobotSetup& setup = findSetup(options.robot);
  if (options.objects < 0 || options.objects > kMaxClutterObjects)
    throw std::invalid_argument(fmt::format("the number of objects must be in [0, {}], got {}",
                                            kMaxClutterObjects, options.objects));
  if (options.target != "glass")
    throw std::invalid_argument(
        fmt::format("unknown target '{}'; the generator knows 'glass'", options.target));
  if (!(options.gap >= 0.0 && options.gap <= 0.2))
    throw std::invalid_argument(
        fmt::format("the gap between objects must be in [0, 0.2] m, got {}", options.gap));

  std::mt19937_64 random(options.seed);
  Placer placer(setup, options);
  const int blockers =
      options.objects >= kBlockersFrom ? std::min(kMaxBlockers, options.objects / 10) : 0;
  for (int b = 0; b < blockers; ++b)
    placer.placeNearGoal(random, b == 0 ? kOnGoalRadius : kNearGoalRadius);
  placer.startRegion(options.objects);
  while (static_cast<int>(placer.cans().size()) < options.objects)
    if (!placer.placeInClutter(random)) break;

  const int placed = static_cast<int>(placer.cans().size());
  if (placed < options.objects)
    throw std::invalid_argument(fmt::format(
        "only {} of {} objects fit on the table with the {} (at least {:g} m apart); ask for "
        "at most {} objects, or a smaller --gap",
        placed, options.objects, options.robot, options.gap, placed));
  return placer.cans();
}

std::string clutterCommandLine(const ClutterOptions& options, const std::string& outputName) {
  std::string line = fmt::format("kautham generate clutter -r {} -n {} -s {}", options.robot,
                                 options.objects, options.seed);
  if (options.gap != ClutterOptions().gap) line += fmt::format(" -g {}", options.gap);
  if (options.layout != ClutterOptions().layout) line += " -l " + options.layout;
  if (options.mix) line += " -m";
  return line + " -o " + outputName;
}

std::string clutterProblemXml(const ClutterOptions& options, const std::vector<CanPlacement>& cans,
                              const std::string& problemName, const std::string& commandLine) {
  const RobotSetup& setup = findSetup(options.robot);
  const Point goal = goalPoint(setup);
  std::string blocking = "No can stands within 5 cm of the pre-grasp point.";
  const auto blockers = std::count_if(cans.begin(), cans.end(), [](auto& c) { return c.blocker; });
  if (blockers > 0)
    blocking = blockers == 1 ? "can1 stands on the pre-grasp point: the robot has to push."
                             : fmt::format(
                                   "can1 stands on the pre-grasp point and can2{} next to it: "
                                   "the robot has to push.",
                                   blockers == 3 ? " and can3" : "");

  std::string xml = "<?xml version=\"1.0\"?>\n";
  xml += fmt::format(
      "<!-- {}\n"
      "     {} movable cans stand between the robot and the glass and around it, placed at "
      "random\n"
      "     without overlap (docs/scenes.md).\n"
      "     {}\n"
      "     Made by: {} -->\n",
      setup.description, cans.size(), blocking, escapeComment(commandLine));
  xml += fmt::format("<Problem name=\"{}\">\n", escapeAttribute(problemName));
  xml += fmt::format("  <Robot robot=\"{}\" name=\"{}\">\n", setup.urdf, setup.name);
  xml += fmt::format("    <!-- {} -->\n", setup.homeComment);
  xml += fmt::format("    <Home {}/>\n", setup.home);
  xml += "  </Robot>\n";
  xml += fmt::format("  <Controls robot=\"{}\"/>\n\n", setup.controls);
  xml += obstacleXml("objects/table.urdf", "fixed", "table", "0", "0", "0.75");
  xml += obstacleXml("objects/glass.urdf", "target", "glass", metres(setup.target.x),
                     metres(setup.target.y), "0.825");
  for (std::size_t i = 0; i < cans.size(); ++i)
    xml += obstacleXml("objects/can.urdf", "movable", fmt::format("can{}", i + 1),
                       metres(cans[i].x), metres(cans[i].y), "0.811");
  xml += "\n" + tablePhysicsXml();
  xml += fmt::format("  <Workspace min=\"{}\" max=\"{}\"/>\n\n", setup.workspaceMin,
                     setup.workspaceMax);
  xml +=
      "  <Planner>\n"
      "    <Parameters>\n"
      "      <Name>KPIECE</Name>\n"
      "      <Parameter name=\"_Max Planning Time\">60</Parameter>\n"
      "      <Parameter name=\"PropagationStepSize\">0.05</Parameter>\n"
      "      <Parameter name=\"Min Control Steps\">2</Parameter>\n"
      "      <Parameter name=\"Max Control Steps\">20</Parameter>\n"
      "      <Parameter name=\"Goal Bias\">0.05</Parameter>\n"
      "    </Parameters>\n"
      "    <Queries>\n"
      "      <Query name=\"pregrasp\">\n";
  xml += fmt::format("        <!-- {} -->\n", setup.initComment);
  xml += fmt::format("        <Init>{}</Init>\n", setup.init);
  xml += fmt::format(
      "        <!-- the pre-grasp point: ({}, {}, 0.825), {} m in front of the glass -->\n",
      metres(goal.x), metres(goal.y), metres(setup.goalOffsetY));
  xml += fmt::format(
      "        <GoalRegion link=\"{}\" relativeTo=\"glass\" offset=\"0 -{} 0\" "
      "tolerance=\"0.03\"\n"
      "                    approach=\"0 0 -1\" approachTolerance=\"0.6\"/>\n",
      setup.goalLink, metres(setup.goalOffsetY));
  xml +=
      "      </Query>\n"
      "    </Queries>\n"
      "  </Planner>\n"
      "</Problem>\n";
  return xml;
}

}  // namespace kautham::apps

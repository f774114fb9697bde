#include "SideGraspClutter.h"

#include <algorithm>
#include <random>
#include <stdexcept>

#include <fmt/format.h>

#include "PlacementMath.h"

namespace kautham::apps {

namespace {

using namespace placement;

constexpr int kBlockersFrom = 10;          // from this many objects on, some block the approach
constexpr int kAttemptsPerObject = 20000;  // failed samples before an object is given up
// The first blocker's centre is drawn within 2 cm across the pre-grasp and from the finger
// roots to 2 cm past the TCP; the target's clearance rejects the part ahead, so it stands
// 2-6 cm (KUKA) or 2-4.5 cm (YuMi) behind the pre-grasp, in the free space.
constexpr Units kFreeSpaceSlack = 200;
/// A rectangle of the table, axis-aligned.
struct Rect {
  Units xmin, xmax, ymin, ymax;
};

/// What the generator knows of an object model: its footprint and where it stands.
struct ObjectModel {
  const char* kind;
  const char* urdf;
  Units radius;    ///< of a disc that holds its footprint (a box's circumscribed circle)
  Units halfSide;  ///< of its footprint's bounding square (upright, unturned): what check uses
  const char* z;   ///< its frame's height when it stands on the table
};

const ObjectModel& objectModel(const std::string& kind) {
  static const ObjectModel models[] = {
      {"can", "objects/can.urdf", 330, 330, "0.811"},
      {"box", "objects/box.urdf", 425, 300, "0.80"},
      {"bottle", "objects/bottle.urdf", 350, 350, "0.875"},
  };
  for (const ObjectModel& model : models)
    if (kind == model.kind) return model;
  throw std::logic_error("unknown object kind " + kind);
}

/// Everything fixed per robot. The numbers come from the robots' kinematics (docs/scenes.md
/// gives them; tests/apps/GenerateCommandTest.cpp checks the start and the goal).
/// The approach is along +y for both robots: from the robot (its arm's shoulder) to the target.
struct SideSetup {
  const char* key;
  const char* description;
  const char* urdf;
  const char* name;
  const char* home;
  const char* controls;
  const char* init;
  const char* initComment;
  const char* goalLink;
  const char* targetUrdf;
  const char* targetName;
  const char* targetZ;
  Point target;
  Units targetRadius;
  const char* graspZOffset;    ///< grasp height above the target's frame, m
  Units pregraspOffset;        ///< the TCP's distance before the target's centre, along +y
  const char* levelAxis;       ///< the fingers' opening axis in the TCP frame
  Units freeWidth;             ///< the free space's width across the approach (fingers and gap)
  Units freeBehind;            ///< the free space reaches this far behind the TCP (finger length)
  Units freeAhead;             ///< and this far ahead (past the target's centre)
  Rect zone;                   ///< where object centres may be
  std::vector<Rect> keepOuts;  ///< footprints of the robot's low parts at the start
  const char* workspaceMin;
  const char* workspaceMax;
  /// Planner parameters of this robot's scenes beyond the common ones (XML lines, or "").
  const char* plannerParameters;
  /// The arm pushes here: QuickStep must follow it through a push more closely than the
  /// top-down scenes' 20 plain iterations do (docs/physics.md, "How many solver iterations").
  SolverSettings solver;
};

const std::vector<SideSetup>& sideSetups() {
  static const std::vector<SideSetup> setups = {
      {"kuka",
       "A KUKA LWR 4+ with a two-finger gripper stands on a 25 cm stand at the side of the table\n"
       "     and must bring its open gripper to a side pre-grasp of a cylinder at the back of the\n"
       "     clutter: gripper level, fingers open around the cylinder's upper part.",
       "robots/kuka_lwr4.urdf",
       "kuka",
       R"(X="0.0" Y="-0.5" Z="1.0" WX="0" WY="0" WZ="1" TH="1.5707963")",
       "robots/controls/kuka_lwr4_arm_open.cntr",
       "0.5 0.7387 0.5 0.0225 0.5 0.1586 0.5",
       "A2 = +57 deg, A4 = -115 deg, A6 = -82 deg: the arm is drawn back and up, the gripper\n"
       "             level and pointing at the target; TCP at (0, 0.06, 1.14), 32 cm from the "
       "pre-grasp.",
       "kuka_tcp",
       "objects/cylinder.urdf",
       "cylinder",
       "0.82",
       {0, 2500},
       350,
       "0.03",
       550,
       "0 1 0",
       1200,
       600,
       950,
       {-3000, 3000, -3200, 3470},
       {},
       "-0.5 -0.4 0.77",
       "0.5 0.4 1.45",
       "      <!-- most expansions follow the goal steering (the clearing pushes, then the\n"
       "           approach): at 0.2 kuka_clutter_10 took 6.3 s and kuka_clutter_20 solved 8 of\n"
       "           10; at 0.8 2.6 s and 10 of 10 (docs/benchmarks.md, session 15) -->\n"
       "      <Parameter name=\"Goal Bias\">0.8</Parameter>\n"
       "      <!-- the approach points the gripper 0.2 rad down (the goal allows 0.3): the wrist\n"
       "           rides higher over the cans behind the pre-grasp; kuka_clutter_20 then\n"
       "           tipped a can in 8.1 % of executions, not 12.6 % (docs/benchmarks.md,\n"
       "           session 16) -->\n"
       "      <Parameter name=\"approach_pitch\">0.2</Parameter>\n"
       "      <!-- the tree starts afresh only after 500 expansions without coming 1 cm nearer\n"
       "           the goal: at 150 kuka_clutter_30's trees were thrown away while they cleared\n"
       "           the corridor; pKP (with goal_shift) solved 4 of 10 at 500, 1 of 10 at 150\n"
       "           (docs/benchmarks.md, session 24) -->\n"
       "      <Parameter name=\"restart_after\">500</Parameter>\n"
       "      <!-- and once it holds 800 motions without a plan, however it is getting on: one\n"
       "           tree solves kuka_clutter_30 within 262-678 motions or not for thousands; pKP\n"
       "           solved it 30 of 30 times, median 8.9 s, not 27 of 30 in 20 s; at 5-20 objects\n"
       "           no tree grows that far (docs/benchmarks.md, session 35) -->\n"
       "      <Parameter name=\"tree_motions\">800</Parameter>\n"
       "      <!-- a candidate whose first 5 particles all succeed is judged by them alone, by\n"
       "           all 15 otherwise (a sequential test): pKPU solved yumi_clutter_30 7 of 10\n"
       "           times, not 2, and kuka_clutter_30 4, not 3; at 10 and 20 objects in 0.57-0.77\n"
       "           times the median time, its plans executing as well (docs/benchmarks.md,\n"
       "           session 41) -->\n"
       "      <Parameter name=\"certain_after\">5</Parameter>\n"
       "      <!-- where a can reaches a little into the free space at the goal point, the\n"
       "           gripper may end up to 7.5 mm from it (within the 1 cm margin), turned up to\n"
       "           0.15 rad, where the free space is clear: kuka_clutter_30's can20, behind the\n"
       "           target, cannot be pushed without touching it (docs/planners.md, session 24) "
       "-->\n"
       "      <Parameter name=\"goal_shift\">0.0075</Parameter>\n"
       "      <!-- where a stand-off has no room for the gripper, 12 cm wide, it is lowered up\n"
       "           to 10 cm back along the approach, where it has room, and slides in low:\n"
       "           lowered onto the stand-off, the fingers tipped the cans beside it. pKP solved\n"
       "           kuka_clutter_30 8 of 10 times, not 4 (26 of 30 over seeds 1-30), its plans\n"
       "           succeeding in a median 34.5 % of executions, not 0; at 5-20 objects 2 of\n"
       "           pKP's 30 plans and 3 of pKPU's and pKPV's 60 changed, and execute alike\n"
       "           (docs/benchmarks.md, session 32) -->\n"
       "      <Parameter name=\"crowded_slide\">0.1</Parameter>\n"
       "      <!-- between pushes the gripper moves at 0.5 m/s, and pushes at 0.2 m/s, not 0.3\n"
       "           and 0.1: the control noise drifts the arm for as long as the plan lasts;\n"
       "           with 40 solver iterations kuka_clutter_20's execution median (pKPV) was\n"
       "           82.5 % at 0.3 and 0.1, 95 % at 0.5 and 0.2 (docs/benchmarks.md, session 27;\n"
       "           at 20 iterations the faster pushes tipped cans) -->\n"
       "      <Parameter name=\"move_speed\">0.5</Parameter>\n"
       "      <Parameter name=\"push_speed\">0.2</Parameter>\n",
       {40, 1.3,
        "  <!-- 40 solver iterations, not 20: at 20 the arm pushing the cans ends a 0.05 s step\n"
        "       1.3 mm (95th percentile 5.5 mm) from where a converged solver (1000) puts it, and\n"
        "       pushed cans tip that would not; at 40, 0.5 mm (1.9 mm). kuka_clutter_20's plans\n"
        "       succeeded in a median 77.5 % of executions at 20, 95 % at 40 with the faster\n"
        "       moves below (docs/physics.md, docs/benchmarks.md, session 27); 20 iterations\n"
        "       over-relaxed at 1.7 follow the arm as closely but not the cans: 81 % (session\n"
        "       28) -->\n"}},
      {"yumi",
       "An ABB YuMi stands on the table and must bring its left gripper, open, to a side\n"
       "     pre-grasp of a slim glass at the back of the clutter: gripper level, fingers open\n"
       "     around the glass.",
       "robots/yumi.urdf",
       "yumi",
       R"(X="0.0" Y="-0.3" Z="0.75" WX="0" WY="0" WZ="1" TH="1.5707963")",
       "robots/controls/yumi_left_arm_open.cntr",
       "0.3397 0.2856 0.9063 0.8918 0.3786 0.7651 0.4645",
       "normalized left arm axes 1, 2, 7, 3, 4, 5, 6: the left gripper level and pointing at\n"
       "             the glass, TCP at (-0.1, -0.02, 1.0), 27 cm from the pre-grasp, the wrist "
       "clear\n"
       "             of the body; the right arm folded away.",
       "yumi_left_tcp",
       "objects/slim_glass.urdf",
       "glass",
       "0.825",
       {-1000, 2300},
       200,
       "0.005",
       400,
       "1 0 0",
       660,
       450,
       600,
       {-5000, 4000, -700, 3470},
       {{-2500, 2500, -5000, -1000}, {2690, 3310, -930, -60}},
       "-0.55 -0.1 0.77",
       "0.55 0.4 1.2",
       "      <!-- most expansions follow the goal steering, as in the KUKA's scenes: with the\n"
       "           corridor's pushes level (below) yumi_clutter_10 took 3.9 s at 0.8 against\n"
       "           9.0 s at 0.2, and yumi_clutter_20 solved 10 of 10 in 5.9 s against 9 in\n"
       "           13.7 s (docs/benchmarks.md, session 17) -->\n"
       "      <Parameter name=\"Goal Bias\">0.8</Parameter>\n"
       "      <!-- the clearing push held level: the YuMi's wrist rides above the table at the\n"
       "           push height (p-KPIECE's default pitch is for the KUKA's; docs/scenes.md) -->\n"
       "      <Parameter name=\"push_pitch\">0</Parameter>\n"
       "      <!-- the corridor cleared up to 15 cm behind the pre-grasp: pushing a can 20 cm\n"
       "           back, near the YuMi's body, takes the gripper out of the workspace\n"
       "           (docs/benchmarks.md, session 13) -->\n"
       "      <Parameter name=\"clear_behind\">0.15</Parameter>\n"
       "      <!-- the corridor's pushes held level too: pitched 1.2 rad (for the KUKA's\n"
       "           wrist), the YuMi's fingertips push along the workspace's floor and tip\n"
       "           the cans they push (docs/benchmarks.md, session 17) -->\n"
       "      <Parameter name=\"corridor_pitch\">0</Parameter>\n"
       "      <!-- but pitched 1.2 rad where no stand-off beside the can leaves the level\n"
       "           gripper room (the wrist reaches less far back): yumi_clutter_30's first\n"
       "           push (docs/benchmarks.md, session 18) -->\n"
       "      <Parameter name=\"crowded_pitch\">1.2</Parameter>\n"
       "      <!-- and, as the KUKA's, where a stand-off has no room for the open fingers, the\n"
       "           gripper is lowered up to 10 cm back along the approach, where it has room,\n"
       "           and slides in low: lowered onto can1's stand-off on yumi_clutter_25, it came\n"
       "           down against can25. pKPU solved yumi_clutter_25 10 of 10 times in a median\n"
       "           4.1 s, its plans succeeding in a median 80.5 % of executions, not 6 of 10\n"
       "           in 37.6 s at 47.5 % (docs/benchmarks.md, session 48) -->\n"
       "      <Parameter name=\"crowded_slide\">0.1</Parameter>\n"
       "      <!-- the goal steering straight at the pre-grasp, without lining up behind it:\n"
       "           lined up, yumi_clutter_20 solved 0 of 10 (docs/benchmarks.md, session 14;\n"
       "           0 of 6 with goal bias 0.5, session 15) -->\n"
       "      <Parameter name=\"final_approach\">0</Parameter>\n"
       "      <!-- the approach points the gripper 0.2 rad down (the goal allows 0.3): the\n"
       "           forearm rides higher over the cans behind the pre-grasp; yumi_clutter_10\n"
       "           solved 10 of 10, not 8 (docs/benchmarks.md, session 16) -->\n"
       "      <Parameter name=\"approach_pitch\">0.2</Parameter>\n"
       "      <!-- the tree starts afresh after 150 expansions without coming 1 cm nearer the\n"
       "           goal: pKP solved yumi_clutter_30 10 of 10 times, not 7 (docs/benchmarks.md,\n"
       "           session 22); runs at 5-20 objects rarely stall that long (1 of 60 pKPU\n"
       "           runs in session 23) -->\n"
       "      <Parameter name=\"restart_after\">150</Parameter>\n"
       "      <!-- and once it holds 800 motions without a plan, however it is getting on, as\n"
       "           the KUKA's: at the same 3 700 motions pKPU solved yumi_clutter_30 12 of 20\n"
       "           times, not 9; pKP 10 of 10 either way; at 5-20 objects no tree grows that\n"
       "           far (docs/benchmarks.md, session 37) -->\n"
       "      <Parameter name=\"tree_motions\">800</Parameter>\n"
       "      <!-- as the KUKA's: a candidate whose first 5 particles all succeed is judged by\n"
       "           them alone, by all 15 otherwise (a sequential test; docs/benchmarks.md,\n"
       "           session 41) -->\n"
       "      <Parameter name=\"certain_after\">5</Parameter>\n"
       "      <!-- the last move to the pre-grasp at most 0.15 m/s: at full speed the arm lags\n"
       "           and ends 1 cm short; yumi_clutter_10's and _20's execution medians were\n"
       "           84.5 and 80.5 % at full speed, 88.5 and 85.5 % at 0.3 m/s, 90.5 and 89.5 %\n"
       "           at 0.15 (docs/benchmarks.md, sessions 17 and 18) -->\n"
       "      <Parameter name=\"approach_speed\">0.15</Parameter>\n"
       "      <!-- between pushes the gripper moves at 0.5 m/s, not 0.3: the control noise\n"
       "           drifts the arm for as long as a move lasts; yumi_clutter_20's execution\n"
       "           median was 87.5 % at 0.3 and 90 % at 0.5, yumi_clutter_10 took 2.5 s\n"
       "           against 2.8 (docs/benchmarks.md, session 25; the KUKA's were worse) -->\n"
       "      <Parameter name=\"move_speed\">0.5</Parameter>\n"
       "      <!-- and pushes at 0.2 m/s, not 0.1: the shorter the plan, the less the control\n"
       "           noise drifts the arm; yumi_clutter_10's and _20's execution medians (pKPV)\n"
       "           were 93 % at 0.1, 99 and 98 % at 0.2 (docs/benchmarks.md, session 27) -->\n"
       "      <Parameter name=\"push_speed\">0.2</Parameter>\n",
       {20, 1.7,
        "  <!-- 20 solver iterations over-relaxed at 1.7 (ODE's default is 1.3): the arm ends a\n"
        "       0.05 s step as close to where a converged solver puts it as with 40 plain\n"
        "       iterations (yumi_clutter_20: 0.34 mm, 95th percentile 1.0 mm), at half the\n"
        "       cost. pKPU's plans on yumi_clutter_10 and _20 executed as well as at 40 (91.5\n"
        "       and 92 %) and were found in 2.3 and 3.3 s, not 4.0 and 6.3; with the pushes\n"
        "       at 0.2 m/s (below), 99 and 99 % in 1.7 and 2.6 s (docs/physics.md, session 28;\n"
        "       the KUKA's pushed cans need the 40) -->\n"}},
  };
  return setups;
}

const SideSetup& findSideSetup(const std::string& robot) {
  for (const SideSetup& setup : sideSetups())
    if (robot == setup.key) return setup;
  throw std::invalid_argument(
      fmt::format("unknown robot '{}'; expected {}", robot, fmt::join(clutterRobots(), " or ")));
}

Point pregrasp(const SideSetup& s) { return {s.target.x, s.target.y - s.pregraspOffset}; }

constexpr Units kFreeHeight =
    400;  // the free space's height: the fingers' width and 1 cm each side

/// The goal's freeSpace and freeSpaceCenter attributes: the box in the TCP frame, across the
/// fingers along the level axis, kFreeHeight along the other, from the finger roots to past
/// the target's centre along +z.
std::string freeSpaceAttributes(const SideSetup& s) {
  const bool acrossIsY = std::string(s.levelAxis) == "0 1 0";
  const Units x = acrossIsY ? kFreeHeight : s.freeWidth;
  const Units y = acrossIsY ? s.freeWidth : kFreeHeight;
  return fmt::format("freeSpace=\"{} {} {}\" freeSpaceCenter=\"0 0 {}\"", metres(x), metres(y),
                     metres(s.freeBehind + s.freeAhead), metres((s.freeAhead - s.freeBehind) / 2));
}

/// The approach corridor and the free space, as one rectangle: the strip the open gripper
/// sweeps moving at grasp height along +y from the near edge of the zone to the pre-grasp,
/// then through the free space to past the target's centre.
Rect corridor(const SideSetup& s) {
  const Point goal = pregrasp(s);
  return {goal.x - s.freeWidth / 2, goal.x + s.freeWidth / 2, s.zone.ymin, goal.y + s.freeAhead};
}

Units distanceSquared(Point p, const Rect& r) {
  const Units dx = std::max<Units>({r.xmin - p.x, 0, p.x - r.xmax});
  const Units dy = std::max<Units>({r.ymin - p.y, 0, p.y - r.ymax});
  return squared(dx) + squared(dy);
}

/// The kinds of the objects in order: cans, or with --mix one bottle then boxes and cans
/// alternating, as in the paper's KUKA scene.
std::vector<std::string> objectKinds(const ClutterOptions& options) {
  std::vector<std::string> kinds;
  for (int i = 0; i < options.objects; ++i)
    kinds.push_back(!options.mix ? "can" : i == 0 ? "bottle" : i % 2 ? "box" : "can");
  return kinds;
}

class SidePlacer {
 public:
  SidePlacer(const SideSetup& setup, const ClutterOptions& options)
      : setup_(setup), gap_(static_cast<Units>(options.gap / kUnit + 0.5)) {}

  bool fits(Point p, Units radius) const {
    const Rect& z = setup_.zone;
    if (p.x < z.xmin || p.x > z.xmax || p.y < z.ymin || p.y > z.ymax) return false;
    if (distanceSquared(p, setup_.target) < squared(radius + setup_.targetRadius + gap_))
      return false;
    for (const Rect& box : setup_.keepOuts)
      if (distanceSquared(p, box) < squared(radius + gap_)) return false;
    for (const SceneObject& o : objects_) {
      const Units other = objectModel(o.kind).radius;
      if (distanceSquared(p, Point{o.x, o.y}) < squared(radius + other + gap_)) return false;
    }
    return true;
  }

  /// The footprint's bounding square overlaps the corridor: the rule of `kautham check`
  /// (core::approachBlockers), so that both count the same objects.
  bool isBlocker(Point p, Units halfSide) const {
    const Rect c = corridor(setup_);
    return p.x - halfSide < c.xmax && c.xmin < p.x + halfSide && p.y - halfSide < c.ymax &&
           c.ymin < p.y + halfSide;
  }

  /// Places an object with its centre drawn from `area`; false if it never fits.
  bool place(std::mt19937_64& random, const std::string& kind, const Rect& area) {
    const Units radius = objectModel(kind).radius;
    for (int attempt = 0; attempt < kAttemptsPerObject; ++attempt) {
      const Point p{uniform(random, area.xmin, area.xmax), uniform(random, area.ymin, area.ymax)};
      if (!fits(p, radius)) continue;
      objects_.push_back({kind, p.x, p.y, isBlocker(p, objectModel(kind).halfSide)});
      return true;
    }
    return false;
  }

  const std::vector<SceneObject>& objects() const { return objects_; }

 private:
  const SideSetup& setup_;
  Units gap_;
  std::vector<SceneObject> objects_;
};

/// Where the first blocker's centre is drawn: on the pre-grasp, in the free space.
Rect onPregrasp(const SideSetup& s) {
  const Point goal = pregrasp(s);
  return {goal.x - kFreeSpaceSlack, goal.x + kFreeSpaceSlack, goal.y - s.freeBehind,
          goal.y + kFreeSpaceSlack};
}

/// Where the other blockers' centres are drawn: the corridor, widened so that an object
/// whose footprint only grazes it still counts.
Rect aroundCorridor(const SideSetup& s, Units halfSide) {
  const Rect c = corridor(s);
  return {c.xmin - halfSide + 1, c.xmax + halfSide - 1, c.ymin, c.ymax};
}

void checkOptions(const ClutterOptions& options) {
  if (options.objects < 0 || options.objects > kMaxClutterObjects)
    throw std::invalid_argument(fmt::format("the number of objects must be in [0, {}], got {}",
                                            kMaxClutterObjects, options.objects));
  if (options.target != "glass")
    throw std::invalid_argument(
        fmt::format("unknown target '{}'; the generator knows 'glass'", options.target));
  if (!(options.gap >= 0.0 && options.gap <= 0.2))
    throw std::invalid_argument(
        fmt::format("the gap between objects must be in [0, 0.2] m, got {}", options.gap));
  // The bottle stands as high as the YuMi's gripper at the start, whose keep-outs are sized
  // for cans.
  if (options.mix && options.robot != "kuka")
    throw std::invalid_argument("--mix is for the KUKA; the YuMi's scenes hold cans only");
}

}  // namespace

int requiredBlockers(int objects) { return objects >= kBlockersFrom ? (objects + 4) / 5 : 0; }

int mostObjectsForBlockers(int blockers) {
  int most = 0;
  for (int n = 0; n <= kMaxClutterObjects; ++n)
    if (requiredBlockers(n) <= blockers) most = n;
  return most;
}

std::vector<SceneObject> placeSideGraspClutter(const ClutterOptions& options) {
  checkOptions(options);
  const SideSetup& setup = findSideSetup(options.robot);
  const std::vector<std::string> kinds = objectKinds(options);
  const int blockers = requiredBlockers(options.objects);

  std::mt19937_64 random(options.seed);
  SidePlacer placer(setup, options);
  for (int i = 0; i < options.objects; ++i) {
    const Rect area = i >= blockers ? setup.zone
                      : i == 0      ? onPregrasp(setup)
                                    : aroundCorridor(setup, objectModel(kinds[i]).halfSide);
    if (placer.place(random, kinds[i], area)) continue;
    if (i < blockers)
      throw std::invalid_argument(fmt::format(
          "only {} of the {} blockers that {} objects need fit on the {}'s approach (at least "
          "{:g} m apart); use a smaller --gap, or at most {} objects ({})",
          i, blockers, options.objects, options.robot, options.gap, mostObjectsForBlockers(i),
          i == 0 ? fmt::format("fewer than {} need no blocker", kBlockersFrom)
                 : fmt::format("they need at most {} blocker{}", i, i == 1 ? "" : "s")));
    throw std::invalid_argument(fmt::format(
        "only {} of {} objects fit in the zone with the {} (at least {:g} m apart); ask for at "
        "most {} objects, or a smaller --gap",
        i, options.objects, options.robot, options.gap, i));
  }
  return placer.objects();
}

std::string sideGraspProblemXml(const ClutterOptions& options,
                                const std::vector<SceneObject>& objects,
                                const std::string& problemName, const std::string& commandLine) {
  const SideSetup& s = findSideSetup(options.robot);
  const Point goal = pregrasp(s);
  const Rect c = corridor(s);
  const auto blockers =
      std::count_if(objects.begin(), objects.end(), [](auto& o) { return o.blocker; });

  std::string xml = "<?xml version=\"1.0\"?>\n";
  xml += fmt::format(
      "<!-- {}\n"
      "     {} movable objects stand at random, without overlap, in a fixed zone between the "
      "robot\n"
      "     and the target and around it; {} of them on the pre-grasp or in the approach corridor\n"
      "     (docs/scenes.md).\n"
      "     Made by: {} -->\n",
      s.description, objects.size(), blockers, escapeComment(commandLine));
  xml += fmt::format("<Problem name=\"{}\">\n", escapeAttribute(problemName));
  xml += fmt::format("  <Robot robot=\"{}\" name=\"{}\">\n", s.urdf, s.name);
  xml += fmt::format("    <Home {}/>\n", s.home);
  xml += "  </Robot>\n";
  xml += fmt::format("  <Controls robot=\"{}\"/>\n\n", s.controls);
  xml += obstacleXml("objects/table.urdf", "fixed", "table", "0", "0", "0.75");
  xml += obstacleXml(s.targetUrdf, "target", s.targetName, metres(s.target.x), metres(s.target.y),
                     s.targetZ);
  std::vector<int> counts(3, 0);
  for (const SceneObject& o : objects) {
    const ObjectModel& model = objectModel(o.kind);
    const int number = ++counts[o.kind == "can" ? 0 : o.kind == "box" ? 1 : 2];
    xml += obstacleXml(model.urdf, "movable", o.kind + std::to_string(number), metres(o.x),
                       metres(o.y), model.z);
  }
  xml += "\n" + tablePhysicsXml(s.solver);
  xml += fmt::format("  <Workspace min=\"{}\" max=\"{}\"/>\n\n", s.workspaceMin, s.workspaceMax);
  xml +=
      "  <Planner>\n"
      "    <Parameters>\n"
      "      <Name>p-KPIECE</Name>\n"
      "      <Parameter name=\"_Max Planning Time\">60</Parameter>\n"
      "      <Parameter name=\"PropagationStepSize\">0.05</Parameter>\n"
      "      <Parameter name=\"Min Control Steps\">2</Parameter>\n"
      "      <Parameter name=\"Max Control Steps\">20</Parameter>\n"
      "      <!-- a plan ends only within half the goal's tolerance of the goal point: ended\n"
      "           near the region's edge, an execution misses it as often as it hits; pKP's\n"
      "           plans on yumi_clutter_30 succeeded in 22.7 % of executions on average, not\n"
      "           14.2 % (docs/benchmarks.md, session 21) -->\n"
      "      <Parameter name=\"goal_margin\">0.5</Parameter>\n";
  xml += s.plannerParameters;
  xml +=
      "    </Parameters>\n"
      "    <Queries>\n"
      "      <Query name=\"pregrasp\">\n";
  xml += fmt::format("        <!-- {} -->\n", s.initComment);
  xml += fmt::format("        <Init>{}</Init>\n", s.init);
  xml += fmt::format(
      "        <!-- side pre-grasp: the TCP at ({}, {}, grasp height), {} m before the target's\n"
      "             centre, its +z (the approach) along +y within 0.3 rad, the fingers' axis "
      "level;\n"
      "             no other object in the free space between the open fingers and on to the "
      "grasp;\n"
      "             the approach corridor is the {} m before the pre-grasp -->\n",
      metres(goal.x), metres(goal.y), metres(s.pregraspOffset), metres(goal.y - c.ymin));
  xml += fmt::format(
      "        <GoalRegion link=\"{}\" relativeTo=\"{}\" offset=\"0 -{} {}\" tolerance=\"0.02\"\n"
      "                    approach=\"0 1 0\" approachTolerance=\"0.3\" levelAxis=\"{}\"\n"
      "                    {}\n"
      "                    approachCorridor=\"{}\"/>\n",
      s.goalLink, s.targetName, metres(s.pregraspOffset), s.graspZOffset, s.levelAxis,
      freeSpaceAttributes(s), metres(goal.y - c.ymin));
  xml +=
      "      </Query>\n"
      "    </Queries>\n"
      "  </Planner>\n"
      "</Problem>\n";
  return xml;
}

}  // namespace kautham::apps

#pragma once

#include "kautham/core/Parameter.h"
#include "kautham/planners/PlannerEntry.h"

namespace kautham::planners {

/// The parameters of p-KPIECE (docs/planners.md gives each with the paper's name). Every
/// field's name, default, range and description is declared once, in parameters() below;
/// settings come from there (parameters().read or defaults()), never from this struct alone.
struct PKpieceSettings {
  unsigned candidates;  ///< k: candidate motions sampled per expansion
  /// n_p: particle motions per valid candidate; 0: the nominal run alone judges it (as without
  /// uncertainty), and verifyRuns executions in sampled worlds still judge the whole plan.
  unsigned particles;
  double displacement;     ///< d: most an object may move in one particle motion (m)
  double randomCandidate;  ///< bias: probability of keeping a random valid candidate
  double beliefWeight;     ///< f: weight of the cell belief; <= 0: the number of cells
  double kpieceSelection;  ///< probability of choosing a cell's motion as KPIECE does
  double goalBias;         ///< probability of expanding one of the motions nearest the goal
  double borderFraction;   ///< probability of expanding an exterior cell
  bool uncertainty;        ///< false: one nominal particle, nothing sampled ("pKP")
  /// A candidate ends the search only if the plan it ends is estimated to succeed at least this
  /// often: the path belief to it times the fraction of its particles that end valid in the
  /// goal region (not in the paper: its belief judges validity, not the goal).
  double goalConfidence;
  /// A candidate ends the search only where its nominal run is within this fraction of the
  /// goal's tolerance of the goal point: a plan ending on the region's border is missed by half
  /// of its executions. 1: anywhere in the region.
  double goalMargin;
  /// The nominal runs (the tree's motions) keep every movable object within this fraction of
  /// the scene's maxTilt; particles and verification judge by the scene's limit. A push that
  /// tips a can part way in the nominal physics tips it over in many sampled executions
  /// (docs/benchmarks.md, session 45). 1: the scene's limit.
  double tiltMargin;
  /// The nominal runs keep the target within this fraction of the scene's targetTolerance of
  /// where it started; particles and verification judge by the scene's tolerance. On
  /// yumi_clutter_35 pKP's nominal plans nudge the glass 2-5 mm of the 5 mm allowed, and their
  /// executions move it beyond in about half the runs (docs/benchmarks.md, session 65).
  double targetMargin;
  /// Cells and motions are judged by the belief of the whole path to a motion (the product
  /// of its candidates' beliefs) rather than by the motion's own (docs/planners.md).
  bool pathBelief;
  /// A candidate's particles start from the robot states its parent's particles reached, so
  /// control noise accumulates along a path (false: from the tree's nominal robot state).
  bool robotSpread;
  /// With robotSpread, the spread also carries the whole state of the objects the path has
  /// moved: particle i's can goes on sliding or tipping as it did (false: objects are drawn
  /// from the pose distribution, upright and at rest as the nominal state has them).
  bool objectSpread;
  /// Stop judging a candidate once it cannot beat the best one so far (the same choice).
  bool pruneCandidates;
  /// With pruneCandidates, a candidate's nominal motion is run only when the choice needs it:
  /// in order, until one is kept certain (its belief 1), the rest never run. One whose run
  /// reaches the goal, or a random keep, has every candidate run as before. The choice differs
  /// from running all first only where a candidate after a certain one would have reached the
  /// goal: on the dense suite most expansions keep their first candidate (the goal steering's).
  bool lazyCandidates;
  /// A sequential test (ours): a candidate that does not reach the goal is judged by its first
  /// certainAfter particles alone when every one of them succeeds (belief 1), and by all n_p
  /// otherwise. 0: always all n_p, as the paper.
  unsigned certainAfter;
  /// The kept candidate's belief is measured again by fresh particles: the best of k
  /// estimates is biased upwards (the winner's curse), and the plan's estimated success is a
  /// product of such winners.
  bool confirmBelief;
  /// With confirmBelief, a kept candidate no other estimate was weighed against is judged
  /// again too: an ordinary motion kept because its particles all ended valid (the rest were
  /// never judged), or the random one. Goal candidates are always judged again. Off by default
  /// since session 38: on the dense suite most kept motions are such, and judging them again
  /// cost a third of the planning time for no better plans (docs/planners.md).
  bool confirmUnrivalled;
  /// In a goal-biased expansion, one of the k candidates is aimed at the goal (GoalSteering).
  bool goalSteering;
  /// The goal steering aims by inverse kinematics and a line in joint space
  /// (JointSpaceSteering), not by a Jacobian probed with one physics step per control.
  bool kinematicSteering;
  /// While an object fills the goal's free space, the goal bias grows the motions furthest
  /// along a push that clears it, and steers that push (ClearingPush).
  bool clearingPush;
  /// How far the clearing push points the gripper down (rad), so the wrist rides above the
  /// table.
  double pushPitch;
  /// How far below the pushed object's centre the fingers' middle pushes (m; negative: above).
  double pushBelowCentre;
  /// How fast the goal link pushes (m/s).
  double pushSpeed;
  /// With the clearing push: how far back from the goal point the approach corridor is cleared
  /// first, where the arm stands at the pre-grasp (m; 0: the free space only).
  double clearBehind;
  /// How far the corridor's pushes point the gripper down (rad), so the wrist passes over the
  /// objects behind.
  double corridorPitch;
  /// How far a push points the gripper down (rad) when no stand-off beside the object has room
  /// for it at its own pitch (0: never steeper than its own).
  double crowdedPitch;
  /// How far back along the approach (m) the gripper may be lowered behind a stand-off without
  /// room for it, to slide into it low (PushSettings::crowdedSlide; 0: lowered onto it).
  double crowdedSlide;
  /// How far (rad) each tree after the first may turn a push away from straight across the
  /// approach, at an angle drawn for the tree and the object (PushSettings::angleSpread; 0:
  /// every push across).
  double pushAngleSpread;
  /// With pushAngleSpread, the first tree whose pushes turn: the trees numbered below it push
  /// straight across (PushSettings::angleAfter).
  unsigned pushAngleAfter;
  /// With pushAngleSpread, the trees per generation whose push angles are learned from the
  /// trees before it (PushSettings::angleGeneration; 0: drawn afresh for every tree).
  unsigned pushAngleGeneration;
  /// How far from the goal point a plan may aim to end (m) where an object reaches into the
  /// free space there but not at the nearer end (0: the goal point only).
  double goalShift;
  /// The goal steering's last move goes straight in along the approach from this far behind
  /// the goal point (m; 0: straight at the goal point from wherever the link is).
  double finalApproach;
  /// The goal steering's approach points the gripper down by this much (rad), within the
  /// goal's approach tolerance, so that the wrist and forearm ride higher over the objects
  /// behind the pre-grasp.
  double approachPitch;
  /// The goal steering's last move goes no faster than this (m/s; 0: as fast as the joints
  /// allow).
  double approachSpeed;
  /// How fast the goal steering moves the link elsewhere (m/s): to and up from a push, and to
  /// the line-up point (the push's own speed is pushSpeed).
  double moveSpeed;
  /// Before a plan ends the search, it is executed this many times open loop in sampled
  /// worlds (PlanVerifier); it ends the search only if at least goalConfidence of them
  /// succeed, and as many fresh executions then give its estimated success. 0: the
  /// particles' estimate decides.
  unsigned verifyRuns;
  /// The tree is started afresh from the start state after this many expansions in which the
  /// motion nearest the goal (by the goal bias's ranking) came no centimetre nearer. 0: never.
  unsigned restartAfter;
  /// The tree is started afresh once it holds this many motions without having ended the
  /// search, however it is getting on. 0: never. A tree's time to a plan is heavy-tailed on the
  /// dense scenes (one tree solves kuka_clutter_30 in a few hundred motions or not for
  /// thousands), and a fixed cutoff is the restart rule for such searches (Luby, Sinclair and
  /// Zuckerman 1993).
  unsigned treeMotions;
  /// The search ends once its trees hold this many motions together, as when the time runs out
  /// (0: only the time ends it). A budget in work rather than time: a fixed seed then ends with
  /// the same outcome on a slow machine as on a fast one, where a time limit ends a run on one
  /// machine at a third of the search it reaches on another.
  unsigned maxMotions;
  /// A plan that fails verification starts the tree afresh: grown on, the tree mostly reaches
  /// the goal again through the rejected plan's pushes.
  bool restartOnRejection;
  /// A plan that fails verification teaches the tree: each of its motions weighs the
  /// executions that ran through it into its belief, its particles' belief counting as n_p
  /// runs (a Beta posterior), and every path through it takes the new belief. The particles
  /// judge a motion from a fitted spread of where its parent's particles ended and, with
  /// certainAfter, by a few of them; executions carry everything before it. So the tree turns
  /// from a push that its particles passed and executions do not, and stops offering plans
  /// through it for verification.
  bool learnFromExecutions;
  /// Each tree grows in a process of its own, with random streams of its own (a function of
  /// the seed and the tree's index), `--threads` of them at once; the search ends with the
  /// first tree, in index order, that ends it (a verified plan, or the time). The same plan for
  /// a seed at any --threads; a search that starts trees afresh (tree_motions, restart_after,
  /// restart_on_rejection) uses every core without particle workers. Needs plans 1, aspiration
  /// 0 and max_motions 0.
  bool parallelTrees;
  /// Verified plans to collect before the search ends (needs verification): each one that
  /// passes starts a new tree, and the plan that succeeded most often over its verification
  /// and estimate runs is returned, its estimate measured again by fresh runs. When the time
  /// runs out first, the best of those collected is returned.
  unsigned plans;
  /// The estimated success (a plan's fresh runs, solution_confidence) at which a verified plan
  /// ends the search at once; 0: any does. A plan that passes verification below it is kept,
  /// and the search goes on from a new tree for a better one, for at most `patience` times the
  /// motions it took to find the first; then the best kept is returned. An anytime bar: on an
  /// easy scene the search can afford a better plan, on a hard one it keeps the one it has.
  double aspiration;
  /// With aspiration: after its first verified plan below it, the search may grow its trees by
  /// this many times the motions they held then (a budget in work: the same on any machine).
  double patience;

  /// Each field's parameter, in the order `kautham planners` lists them, plus the projection's
  /// `cell_size` (the framework applies it). A `displacement` of 0 means the problem's
  /// maxDisplacement: the planner's registry entry resolves it.
  static const core::SettingsParameters<PKpieceSettings>& parameters();
};

inline const core::SettingsParameters<PKpieceSettings>& PKpieceSettings::parameters() {
  using core::Parameter;
  using S = PKpieceSettings;
  static const auto table =
      core::SettingsParameters<S>()
          .add(&S::candidates, Parameter::integer("candidates")
                                   .byDefault(5)
                                   .range(1, 1000)
                                   .describe("k: candidate motions sampled per expansion")
                                   .alias("k"))
          .add(&S::particles, Parameter::integer("particles")
                                  .byDefault(15)
                                  .range(0, 10000)
                                  .describe("n_p: particle motions that judge each valid "
                                            "candidate (0: its nominal run alone; with "
                                            "uncertainty and verify_runs, whole plans are "
                                            "still verified in sampled worlds)")
                                  .alias("n_p")
                                  .alias("np"))
          .add(&S::displacement,
               Parameter::real("displacement")
                   .byDefault(0.0)
                   .range(0.0, 100.0)
                   .describe("d: most an object may move in one motion (m); 0: the problem's "
                             "maxDisplacement")
                   .alias("d"))
          .add(&S::randomCandidate,
               Parameter::real("random_candidate")
                   .byDefault(0.05)
                   .range(0.0, 1.0)
                   .describe("bias: probability of keeping a random valid candidate instead of "
                             "the best")
                   .alias("bias"))
          .add(&S::beliefWeight,
               Parameter::real("belief_weight")
                   .byDefault(0.0)
                   .range(0.0, 1e9)
                   .describe("f: weight of the cell belief in the importance; 0: the number of "
                             "cells")
                   .alias("f"))
          .add(&S::kpieceSelection,
               Parameter::real("kpiece_selection")
                   .byDefault(0.1)
                   .range(0.0, 1.0)
                   .describe("probability of choosing a cell's motion as KPIECE does instead of "
                             "by belief"))
          .add(&S::uncertainty,
               Parameter::flag("uncertainty")
                   .byDefault(1)
                   .describe("sample poses, contacts and control noise (0: one nominal particle, "
                             "the paper's pKP)"))
          .add(&S::goalConfidence,
               Parameter::real("goal_confidence")
                   .byDefault(0.5)
                   .range(0.0, 1.0)
                   .describe("estimated success a plan needs to end the search: the path belief "
                             "times the fraction of the last candidate's particles that end "
                             "valid in the goal"))
          .add(&S::goalMargin,
               Parameter::real("goal_margin")
                   .byDefault(1.0)
                   .range(0.05, 1.0)
                   .describe("how deep in the goal region a plan must end: its nominal end within "
                             "this fraction of the goal's tolerance of the goal point (1: "
                             "anywhere in the region; at 0 none could end)"))
          .add(&S::tiltMargin,
               Parameter::real("tilt_margin")
                   .byDefault(1.0)
                   .range(0.05, 1.0)
                   .describe("the tree's nominal motions keep every movable object within this "
                             "fraction of the scene's maxTilt (particles and verification judge "
                             "by the scene's limit; 1: the scene's limit)"))
          .add(&S::targetMargin,
               Parameter::real("target_margin")
                   .byDefault(1.0)
                   .range(0.05, 1.0)
                   .describe("the tree's nominal motions keep the target within this fraction of "
                             "the scene's targetTolerance of its start (particles and "
                             "verification judge by the scene's tolerance; 1: the scene's)"))
          .add(&S::pathBelief,
               Parameter::flag("path_belief")
                   .byDefault(1)
                   .describe("judge cells and motions by the belief of the whole path to them "
                             "(0: by the motion's own)"))
          .add(&S::robotSpread,
               Parameter::flag("robot_spread")
                   .byDefault(1)
                   .describe("particles start from the robot states their parent's particles "
                             "reached, so control noise accumulates along a path (0: from the "
                             "tree's robot state)"))
          .add(&S::objectSpread,
               Parameter::flag("object_spread")
                   .byDefault(1)
                   .describe("with robot_spread, particles also take the objects the path moved "
                             "(pose, tilt, velocities) from their parent's particles (0: drawn "
                             "from the pose distribution)"))
          .add(&S::pruneCandidates,
               Parameter::flag("prune_candidates")
                   .byDefault(1)
                   .describe("stop judging a candidate once it cannot beat the best so far (the "
                             "same choice, less work)"))
          .add(&S::lazyCandidates,
               Parameter::flag("lazy_candidates")
                   .byDefault(1)
                   .describe("with prune_candidates, run a candidate's nominal motion only when "
                             "the choice needs it: in order until one is certain (every one if "
                             "one reaches the goal, or for a random keep); 0: all k first"))
          .add(&S::certainAfter,
               Parameter::integer("certain_after")
                   .byDefault(0)
                   .range(0, 10000)
                   .describe("a sequential test: a candidate that does not reach the goal is "
                             "certain once its first this many particles all succeed, and the "
                             "rest are not run (0: all n_p)"))
          .add(&S::confirmBelief,
               Parameter::flag("confirm_belief")
                   .byDefault(1)
                   .describe("measure the kept candidate's belief again with fresh particles "
                             "(the best of k estimates is biased upwards)"))
          .add(&S::confirmUnrivalled,
               Parameter::flag("confirm_unrivalled")
                   .byDefault(0)
                   .describe("with confirm_belief, also judge again a kept motion whose "
                             "estimate was not weighed against another's (the first judged "
                             "and certain, the only valid one, or the random one); goal "
                             "candidates always are"))
          .add(&S::goalSteering,
               Parameter::flag("goal_steering")
                   .byDefault(1)
                   .describe("in a goal-biased expansion, aim one candidate at the goal "
                             "(kinematic_steering says how)"))
          .add(&S::kinematicSteering,
               Parameter::flag("kinematic_steering")
                   .byDefault(1)
                   .describe("the goal steering aims by inverse kinematics and a straight line "
                             "in joint space (0: by a Jacobian from one physics step per "
                             "control)"))
          .add(&S::clearingPush,
               Parameter::flag("clearing_push")
                   .byDefault(1)
                   .describe("while an object fills the goal's free space, the goal bias grows "
                             "and steers a low push that moves it out sideways"))
          .add(&S::pushPitch,
               Parameter::real("push_pitch")
                   .byDefault(0.45)
                   .range(0.0, 1.5)
                   .describe("how far the clearing push points the gripper down (rad), so the "
                             "wrist rides above the table"))
          .add(&S::pushBelowCentre,
               Parameter::real("push_below_centre")
                   .byDefault(0.015)
                   .range(-0.1, 0.1)
                   .describe("how far below the pushed object's centre the fingers' middle "
                             "pushes (m; negative: above), never lower than the workspace's "
                             "floor allows the goal link"))
          .add(&S::pushSpeed, Parameter::real("push_speed")
                                  .byDefault(0.1)
                                  .range(0.01, 1.0)
                                  .describe("how fast the goal link pushes (m/s): slower "
                                            "leaves the object upright"))
          .add(&S::clearBehind,
               Parameter::real("clear_behind")
                   .byDefault(0.2)
                   .range(0.0, 1.0)
                   .describe("with clearing_push: objects in the approach corridor up to this "
                             "far behind the goal point (m), where the arm stands at the "
                             "pre-grasp, are pushed out first (0: the free space only)"))
          .add(&S::corridorPitch,
               Parameter::real("corridor_pitch")
                   .byDefault(1.2)
                   .range(0.0, 1.5)
                   .describe("how far the corridor's pushes point the gripper down (rad), so "
                             "the wrist passes over the objects behind"))
          .add(&S::crowdedPitch,
               Parameter::real("crowded_pitch")
                   .byDefault(0.0)
                   .range(0.0, 1.5)
                   .describe("how far a push points the gripper down (rad) when no stand-off "
                             "beside the object leaves its footprint room at the push's own "
                             "pitch, if that leaves more (0: never steeper than its own)"))
          .add(&S::crowdedSlide,
               Parameter::real("crowded_slide")
                   .byDefault(0.0)
                   .range(0.0, 0.2)
                   .describe("where a push's stand-off has no room for the whole gripper, lower "
                             "it up to this far back along the approach (m), at the nearest point "
                             "with room (else the roomiest), and slide it in low: the objects in "
                             "the way slide aside instead of tipping under fingers lowered onto "
                             "them (0: lowered onto the stand-off)"))
          .add(&S::pushAngleSpread,
               Parameter::real("push_angle_spread")
                   .byDefault(0.0)
                   .range(0.0, 1.2)
                   .describe("each tree after the first pushes each object at an angle of its "
                             "own, drawn up to this far (rad) from straight across the approach, "
                             "towards the target or away from it: another tree tries other "
                             "pushes (0: every push straight across)"))
          .add(&S::pushAngleAfter,
               Parameter::integer("push_angle_after")
                   .byDefault(1)
                   .range(1, 100000)
                   .describe("with push_angle_spread, the trees numbered from this one on push "
                             "at angles of their own; the ones before push straight across, as "
                             "the first does (1: every tree after the first)"))
          .add(&S::pushAngleGeneration,
               Parameter::integer("push_angle_generation")
                   .byDefault(0)
                   .range(0, 1000)
                   .describe("experimental, measured worse than drawing afresh on the dense "
                             "YuMi scenes: with push_angle_spread, learn the angles: the trees "
                             "from push_angle_after on come in generations of this many, and each "
                             "generation after the first draws each object's angle from a normal "
                             "fitted to the nearest quarter of the trees before it (0: every "
                             "tree draws afresh)"))
          .add(&S::goalShift,
               Parameter::real("goal_shift")
                   .byDefault(0.0)
                   .range(0.0, 0.05)
                   .describe("where an object reaches into the goal's free space at the goal "
                             "point, aim the gripper at the pose up to this far from it (m, "
                             "horizontally) whose free space is clear with the most room, instead "
                             "of pushing it (0: the goal point only; keep it inside the goal "
                             "margin)"))
          .add(&S::finalApproach,
               Parameter::real("final_approach")
                   .byDefault(0.05)
                   .range(0.0, 0.5)
                   .describe("the goal steering lines the gripper up this far behind the goal "
                             "point (m), turned as the goal asks, and then goes straight in "
                             "along the approach (0: straight at the goal point)"))
          .add(&S::approachPitch,
               Parameter::real("approach_pitch")
                   .byDefault(0.0)
                   .range(-0.5, 0.5)
                   .describe("how far the goal steering's approach points the gripper down "
                             "(rad, within the goal's approach tolerance), so the forearm rides "
                             "higher over the objects behind the pre-grasp"))
          .add(&S::approachSpeed,
               Parameter::real("approach_speed")
                   .byDefault(0.0)
                   .range(0.0, 1.0)
                   .describe("how fast the goal steering's last move may go (m/s; 0: as fast as "
                             "the joints allow, which the arm lags and ends short of the goal "
                             "point)"))
          .add(&S::moveSpeed,
               Parameter::real("move_speed")
                   .byDefault(0.3)
                   .range(0.05, 1.0)
                   .describe("how fast the goal steering moves the gripper between pushes: to "
                             "and up from a push, and to the line-up point (m/s)"))
          .add(&S::verifyRuns,
               Parameter::integer("verify_runs")
                   .byDefault(50)
                   .range(0, 100000)
                   .describe("executions of a whole plan in sampled worlds before it may end the "
                             "search (as validate runs it); at least goal_confidence of them must "
                             "succeed (0: the particles' estimate decides)"))
          .add(&S::restartAfter,
               Parameter::integer("restart_after")
                   .byDefault(0)
                   .range(0, 100000000)
                   .describe("start the tree afresh after this many expansions in which the "
                             "motion nearest the goal came no centimetre nearer (0: never)"))
          .add(&S::treeMotions,
               Parameter::integer("tree_motions")
                   .byDefault(0)
                   .range(0, 100000000)
                   .describe("start the tree afresh once it holds this many motions without a "
                             "plan, however it is getting on (0: never)"))
          .add(&S::maxMotions,
               Parameter::integer("max_motions")
                   .byDefault(0)
                   .range(0, 100000000)
                   .describe("end the search once all its trees hold this many motions, as when "
                             "the time runs out: a budget in work, the same on any machine (0: "
                             "the time limit only)"))
          .add(&S::restartOnRejection,
               Parameter::flag("restart_on_rejection")
                   .byDefault(0)
                   .describe("start the tree afresh when a plan fails verification (grown on, "
                             "the tree mostly reaches the goal through the same pushes again)"))
          .add(&S::learnFromExecutions,
               Parameter::flag("learn_from_executions")
                   .byDefault(0)
                   .describe("when a plan fails verification, each of its motions weighs the "
                             "executions that ran through it into its belief (its particles "
                             "counting as the runs they were: n_p, or certain_after), and the "
                             "paths through it take the new beliefs"))
          .add(&S::parallelTrees,
               Parameter::flag("parallel_trees")
                   .byDefault(0)
                   .describe("grow each tree in a process of its own, with random streams of its "
                             "own, --threads at once; the first tree in order that ends the "
                             "search gives the plan, the same at any --threads (needs plans 1, "
                             "aspiration 0, max_motions 0)"))
          .add(&S::plans, Parameter::integer("plans").byDefault(1).range(1, 1000).describe(
                              "verified plans to collect, each from a new tree, before the one "
                              "that succeeded most often is returned (the best so far when the "
                              "time runs out; needs uncertainty and verify_runs > 0)"))
          .add(&S::aspiration,
               Parameter::real("aspiration")
                   .byDefault(0.0)
                   .range(0.0, 1.0)
                   .describe("estimated success at which a verified plan ends the search at "
                             "once (0: any verified plan); one below it is kept and the search "
                             "goes on from a new tree for a better one, for patience times the "
                             "motions it took, then returns the best kept (needs uncertainty and "
                             "verify_runs > 0)"))
          .add(&S::patience,
               Parameter::real("patience")
                   .byDefault(1.0)
                   .range(0.0, 100.0)
                   .describe("with aspiration: motions the search may still grow after its first "
                             "verified plan below it, as a multiple of the motions it held then"))
          // Measured on kuka_cans_10: 0.2 solves more seeds, with shorter plans, than 0.05.
          .add(&S::goalBias, goalBiasParameter(0.2))
          .add(&S::borderFraction, Parameter::real("border_fraction")
                                       .byDefault(0.8)
                                       .range(0.0, 1.0)
                                       .describe("probability of expanding an exterior cell")
                                       .alias("Border Fraction"))
          .add(cellSizeParameter());
  return table;
}

}  // namespace kautham::planners

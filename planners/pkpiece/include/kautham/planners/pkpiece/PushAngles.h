#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace kautham::planners {

/// The angles at which p-KPIECE's trees push each object away from straight across the approach
/// (ours, not in the paper): the push_angle_spread, push_angle_after and push_angle_generation
/// parameters.
///
/// Trees numbered below `after` push straight across. From `after` on, a tree pushes each
/// object at an angle of its own, fixed for the whole tree: drawn uniformly within `spread` of
/// straight from a hash of the search's seed, the tree and the object, so it depends on nothing
/// else (not on how many trees grow at once). The seed is in the hash so that runs with other
/// seeds draw other angles: a benchmark over seeds samples the angles, not one lucky sequence.
///
/// With `generation` > 0 the angles are learned instead of drawn afresh. The trees from `after`
/// on come in generations of `generation` trees. The first draws uniformly, as above. Each
/// later one draws each object's angle from a normal distribution fitted to the angles of the
/// best quarter (at least three) of all trees with angles before it, ranked by how near each got
/// to the goal (its best GoalSteering::learningRank, which does not depend on the angles). This is
/// the cross-entropy method; it suits the dense scenes, where the first few pushes' angles decide
/// whether a tree can reach the goal at all (docs/planners.md, "Push angles learned from the
/// trees").
///
/// A generation's fit depends only on the trees before it, so a tree's angles do not depend on
/// how many trees grow at once. The cost is a wait: a tree of a later generation can start only
/// once every tree before its generation has been recorded (treesBefore()).
class PushAngles {
 public:
  struct Settings {
    double spread = 0.0;           ///< rad a push may turn either way (0: every push straight)
    std::uint64_t after = 1;       ///< the first tree whose pushes turn
    std::uint64_t generation = 0;  ///< trees per generation (0: every tree draws afresh)
    std::uint64_t seed = 0;        ///< the search's seed: another seed, other angles
  };

  /// `bodies`: how many bodies the world has (angles are asked by body index).
  PushAngles(const Settings& settings, std::size_t bodies);

  /// Which tree angle() answers for. Fits the distributions its generation draws from; throws
  /// std::logic_error when a tree before that generation has not been recorded.
  void setTree(std::uint64_t tree);
  /// The angle (rad, towards the target positive) at which the current tree pushes `body`.
  double angle(std::size_t body) const;

  /// Whether later trees learn from earlier ones (a spread and generations).
  bool learns() const { return settings_.spread > 0.0 && settings_.generation > 0; }
  /// How near `tree` got to the goal: its best rank (lower is nearer).
  void record(std::uint64_t tree, double rank);
  /// Forgets every tree recorded (a new search) and goes back to tree 0.
  void forget();
  /// How many trees (0, 1, ...) must be recorded before `tree` can start.
  std::uint64_t treesBefore(std::uint64_t tree) const;

 private:
  struct Normal {
    double mean = 0.0;
    double sd = 0.0;
  };
  /// The generation of `tree` (0 below `after`, and without generations).
  std::uint64_t generationOf(std::uint64_t tree) const;
  /// The first tree of `generation`.
  std::uint64_t generationStart(std::uint64_t generation) const;
  /// The angle at which `tree` pushes `body`, with the fits that tree's generation needs made.
  double angleOf(std::uint64_t tree, std::size_t body) const;
  /// Fits generation fits_.size() + 1's distributions to the trees before it.
  void fitNextGeneration();

  Settings settings_;
  std::size_t bodies_;
  std::vector<double> current_;  ///< by body: the angles of the tree setTree() was given
  std::vector<double> ranks_;    ///< by tree; NaN: not recorded
  /// fits_[g - 1][body]: what generation g (>= 1) draws from.
  std::vector<std::vector<Normal>> fits_;
};

}  // namespace kautham::planners

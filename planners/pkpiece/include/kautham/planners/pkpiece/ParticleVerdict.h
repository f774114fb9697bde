#pragma once

#include <cstddef>
#include <vector>

namespace kautham::planners {

/// What the particles of a candidate said (the paper's Algorithm 2, lines 5-17), particle by
/// particle, and the fractions that make its belief.
struct ParticleVerdict {
  unsigned particles = 0;      ///< n_p: the particles asked for (0: the nominal run judged)
  double stateValidity = 1.0;  ///< P_state: fraction of particles whose states were all valid
  double interaction = 1.0;    ///< P_int: fraction whose objects moved at most d
  double goal = 1.0;           ///< fraction of particles that end valid inside the goal region
  /// Stopped early: its belief could no longer beat the one it had to (the numbers above then
  /// describe only the particles that ran).
  bool pruned = false;

  std::vector<std::vector<double>> starts;  ///< each particle's start state (its sampled poses)
  std::vector<std::vector<double>> ends;    ///< each particle's final state
  std::vector<char> endValid;               ///< each particle's states were all valid
  std::vector<char> endInteractionOk;       ///< each particle's objects moved at most d
  std::vector<char> endInGoal;  ///< each particle ended valid, within d, in its goal region
  /// Per particle: its valid states after the request's recordAfter steps (ParticleResult),
  /// and for each whether it was inside the particle's goal and its objects had moved at most
  /// d by then.
  std::vector<std::vector<std::vector<double>>> recorded;
  std::vector<std::vector<char>> recordedInGoal;
  std::vector<std::vector<char>> recordedInteractionOk;

  double belief() const { return stateValidity * interaction; }
  /// Sets the three fractions from the particles so far (`particles` is the denominator).
  void tally();
  /// Particles whose recorded state `record` exists and is in their goal.
  unsigned inGoalAt(std::size_t record) const;
  /// The verdict of the motion cut after the step of record `record`: a particle is valid if
  /// it was then, and ends there; records after it are dropped.
  ParticleVerdict cutAt(std::size_t record) const;
};

}  // namespace kautham::planners

#include "kautham/planners/pkpiece/PushAngles.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>

#include "kautham/core/Random.h"

namespace kautham::planners {

namespace {
// The share of the trees before a generation whose angles it is fitted to: the nearest ones.
constexpr double kEliteShare = 0.25;
// Fitted to fewer trees than this, a spread means nothing.
constexpr std::size_t kMinElite = 3;
// A fitted distribution keeps at least this spread (rad), so that a generation still tries
// angles a little off the best ones: a can's push of 0.05 rad more or less changes little.
constexpr double kMinSd = 0.05;

// The key of `tree`'s draw for `body` under `seed`: the same object is pushed at the same angle
// all through a tree, whatever state the push is steered from.
std::uint64_t keyOf(std::uint64_t seed, std::uint64_t tree, std::size_t body) {
  return core::mix64(core::mix64(seed) ^ tree * 0x9E3779B97F4A7C15ULL ^
                     (body + 1) * 0xBF58476D1CE4E5B9ULL);
}
}  // namespace

PushAngles::PushAngles(const Settings& settings, std::size_t bodies)
    : settings_(settings), bodies_(bodies), current_(bodies, 0.0) {
  // The first tree pushes straight whatever the setting: its plans stay those of the search
  // without the spread.
  settings_.after = std::max<std::uint64_t>(settings_.after, 1);
}

std::uint64_t PushAngles::generationOf(std::uint64_t tree) const {
  if (settings_.generation == 0 || tree < settings_.after) return 0;
  return (tree - settings_.after) / settings_.generation;
}

std::uint64_t PushAngles::generationStart(std::uint64_t generation) const {
  return settings_.after + generation * settings_.generation;
}

std::uint64_t PushAngles::treesBefore(std::uint64_t tree) const {
  const std::uint64_t generation = generationOf(tree);
  return generation == 0 ? 0 : generationStart(generation);
}

void PushAngles::setTree(std::uint64_t tree) {
  if (settings_.spread > 0.0)
    while (fits_.size() < generationOf(tree)) fitNextGeneration();
  // Drawn once per tree: the steering asks for an object's angle several times per motion.
  for (std::size_t body = 0; body < bodies_; ++body) current_[body] = angleOf(tree, body);
}

double PushAngles::angle(std::size_t body) const { return current_.at(body); }

double PushAngles::angleOf(std::uint64_t tree, std::size_t body) const {
  if (tree < settings_.after || settings_.spread <= 0.0) return 0.0;
  const std::uint64_t key = keyOf(settings_.seed, tree, body);
  const std::uint64_t generation = generationOf(tree);
  if (generation == 0) {
    const double unit = static_cast<double>(key >> 11) * 0x1.0p-53;  // in [0, 1)
    return settings_.spread * (2.0 * unit - 1.0);
  }
  const Normal& fit = fits_.at(generation - 1).at(body);
  std::mt19937_64 draw(key);
  return std::clamp(fit.mean + fit.sd * core::standardNormal(draw), -settings_.spread,
                    settings_.spread);
}

void PushAngles::fitNextGeneration() {
  const std::uint64_t generation = fits_.size() + 1;
  const std::uint64_t end = generationStart(generation);
  std::vector<std::uint64_t> trees;
  for (std::uint64_t t = settings_.after; t < end; ++t) {
    if (t >= ranks_.size() || std::isnan(ranks_[t]))
      throw std::logic_error("p-KPIECE: tree " + std::to_string(t) +
                             " must be settled before the push angles of generation " +
                             std::to_string(generation) + " are fitted");
    trees.push_back(t);
  }
  // The nearest trees first; of two as near, the earlier (a stable order, the same every run).
  std::stable_sort(trees.begin(), trees.end(),
                   [this](std::uint64_t a, std::uint64_t b) { return ranks_[a] < ranks_[b]; });
  const std::size_t elite = std::min(
      trees.size(),
      std::max(kMinElite, static_cast<std::size_t>(std::ceil(kEliteShare * trees.size()))));
  std::vector<Normal> fit(bodies_);
  for (std::size_t body = 0; body < bodies_; ++body) {
    double sum = 0.0;
    double squares = 0.0;
    for (std::size_t i = 0; i < elite; ++i) {
      const double a = angleOf(trees[i], body);
      sum += a;
      squares += a * a;
    }
    const double mean = sum / static_cast<double>(elite);
    const double variance = std::max(0.0, squares / static_cast<double>(elite) - mean * mean);
    fit[body] = {mean, std::max(kMinSd, std::sqrt(variance))};
  }
  fits_.push_back(std::move(fit));
}

void PushAngles::record(std::uint64_t tree, double rank) {
  if (ranks_.size() <= tree) ranks_.resize(tree + 1, std::numeric_limits<double>::quiet_NaN());
  // A tree that never ranked (no motion) counts as the furthest.
  ranks_[tree] = std::isnan(rank) ? std::numeric_limits<double>::infinity() : rank;
}

void PushAngles::forget() {
  ranks_.clear();
  fits_.clear();
  std::fill(current_.begin(), current_.end(), 0.0);
}

}  // namespace kautham::planners

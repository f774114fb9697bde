#include "kautham/planners/pkpiece/ParticleVerdict.h"

#include <algorithm>

namespace kautham::planners {

unsigned ParticleVerdict::inGoalAt(std::size_t record) const {
  unsigned count = 0;
  for (const auto& inGoal : recordedInGoal)
    count += record < inGoal.size() && inGoal[record] ? 1 : 0;
  return count;
}

void ParticleVerdict::tally() {
  if (particles == 0) return;  // the nominal run judged: the fractions were set directly
  const auto fraction = [this](const std::vector<char>& flags) {
    return static_cast<double>(std::count(flags.begin(), flags.end(), 1)) / particles;
  };
  stateValidity = fraction(endValid);
  interaction = fraction(endInteractionOk);
  goal = fraction(endInGoal);
}

ParticleVerdict ParticleVerdict::cutAt(std::size_t record) const {
  ParticleVerdict cut = *this;
  for (std::size_t p = 0; p < recorded.size(); ++p) {
    // A particle without this record was invalid before the cut: it ends where it did,
    // judged as it was.
    if (record >= recorded[p].size()) continue;
    cut.ends[p] = recorded[p][record];
    cut.endValid[p] = 1;
    cut.endInteractionOk[p] = recordedInteractionOk[p][record];
    cut.endInGoal[p] = recordedInGoal[p][record];
    cut.recorded[p].resize(record + 1);
    cut.recordedInGoal[p].resize(record + 1);
    cut.recordedInteractionOk[p].resize(record + 1);
  }
  cut.tally();
  return cut;
}

}  // namespace kautham::planners

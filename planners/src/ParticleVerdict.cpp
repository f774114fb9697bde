#include "kautham/planners/ParticleVerdict.h"

namespace kautham::planners {

unsigned ParticleVerdict::inGoalAt(std::size_t record) const {
  unsigned count = 0;
  for (const auto& inGoal : recordedInGoal)
    count += record < inGoal.size() && inGoal[record] ? 1 : 0;
  return count;
}

ParticleVerdict ParticleVerdict::cutAt(std::size_t record) const {
  ParticleVerdict cut = *this;
  unsigned valid = 0;
  unsigned interactionOk = 0;
  for (std::size_t p = 0; p < recorded.size(); ++p) {
    if (record < recorded[p].size()) {
      ++valid;
      interactionOk += recordedInteractionOk[p][record] ? 1 : 0;
      cut.ends[p] = recorded[p][record];
      cut.endInteractionOk[p] = recordedInteractionOk[p][record];
      cut.recorded[p].resize(record + 1);
      cut.recordedInGoal[p].resize(record + 1);
      cut.recordedInteractionOk[p].resize(record + 1);
    } else {
      // Invalid before the cut: it ends where it did, judged as it was.
      interactionOk += endInteractionOk[p] ? 1 : 0;
    }
  }
  if (particles > 0) {
    cut.stateValidity = static_cast<double>(valid) / particles;
    cut.interaction = static_cast<double>(interactionOk) / particles;
    cut.goal = static_cast<double>(inGoalAt(record)) / particles;
  }
  return cut;
}

}  // namespace kautham::planners

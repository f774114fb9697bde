#pragma once

namespace kautham::planners {

/// A motion's belief once executions of rejected plans have run through it
/// (learn_from_executions): the mean of a Beta posterior whose prior is its particles' belief,
/// counted as the particles that judged it (n_p, or certain_after when the first ones all
/// succeeded). So a motion that few particles found certain yields sooner to executions that
/// say otherwise than one that all n_p particles judged. Without particles (particleRuns 0) it
/// is the executions' rate; with neither particles nor executions, the particles' belief.
double beliefAfterExecutions(double particleBelief, unsigned particleRuns, unsigned began,
                             unsigned gotThrough);

}  // namespace kautham::planners

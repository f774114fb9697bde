#pragma once

// Kautham's planner names (<Name> in a problem's <Planner>), mapped onto this project's.

#include <optional>
#include <string>

#include "kautham/core/Problem.h"

namespace kautham::apps {

/// What a Kautham planner name means here.
struct KauthamPlanner {
  enum class Kind { Ours, Mapped, Geometric, Unknown };
  Kind kind = Kind::Unknown;
  std::string planner;  ///< ours (Ours, Mapped); the suggested --planner (Geometric)
  std::string note;     ///< one line for the user (Mapped, Geometric)
};

/// Classifies the problem's planner name: one of ours; a Kautham physics or control planner that
/// maps onto one of ours (KnowledgeOrientedKPIECE2DPlanner -> o-KPIECE, KPIECEChainPlanner ->
/// KPIECE, omplcRRT... -> RRT, omplcSST... -> SST); a geometric OMPL planner of Kautham
/// (omplRRTConnect, omplPRM, ...), which has no counterpart yet; or unknown.
KauthamPlanner classifyPlanner(const std::string& name);

/// The planner a command should use: `override` (--planner) when given; else the file's, mapped
/// when it is a Kautham name. For a geometric Kautham planner, `plan` gets an InputError at the
/// <Name> line saying which --planner to use; `check` (lenient) warns and checks with that one.
/// Returns nothing to use the file's name as it is.
std::optional<std::string> plannerToUse(const core::Problem& problem,
                                        const std::optional<std::string>& override, bool lenient);

}  // namespace kautham::apps

#include "KauthamPlanners.h"

#include <map>

#include "kautham/core/InputError.h"
#include "kautham/core/Log.h"
#include "kautham/planners/PlannerRegistry.h"

namespace kautham::apps {

namespace {

bool startsWith(const std::string& text, const std::string& prefix) {
  return text.rfind(prefix, 0) == 0;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

KauthamPlanner mapped(const std::string& name, const std::string& ours, const std::string& what) {
  return {KauthamPlanner::Kind::Mapped, ours,
          "planner '" + name + "' is Kautham's " + what + "; planned here with '" + ours + "'"};
}

/// Kautham's geometric OMPL planners (omplRRTConnect, omplPRM, ...) onto ours of the same
/// algorithm; the ones without a counterpart get the list of those there are.
KauthamPlanner geometric(const std::string& name) {
  static const std::map<std::string, std::string> ours{
      {"omplRRTConnect", "RRTConnect"},   {"omplRRT", "RRT-geometric"}, {"omplRRTStar", "RRTstar"},
      {"omplRRTstar", "RRTstar"},         {"omplPRM", "PRM"},           {"omplLazyRRT", "LazyRRT"},
      {"omplKPIECE", "KPIECE-geometric"}, {"omplEST", "EST-geometric"}, {"omplBITstar", "BITstar"},
      {"omplpRRT", "RRT-geometric"}};
  const auto found = ours.find(name);
  if (found != ours.end())
    return mapped(name, found->second,
                  std::string("geometric OMPL planner") +
                      (name == "omplpRRT" ? " (parallel RRT; run here as one RRT)" : ""));
  return {KauthamPlanner::Kind::Geometric, "RRTConnect",
          "planner '" + name +
              "' is one of Kautham's geometric OMPL planners that this program does not have; "
              "use --planner with one it has: RRTConnect, RRT-geometric, RRTstar, PRM, LazyRRT, "
              "KPIECE-geometric, EST-geometric, BITstar"};
}

}  // namespace

KauthamPlanner classifyPlanner(const std::string& name) {
  if (planners::plannerRegistry().find(name)) return {KauthamPlanner::Kind::Ours, name, ""};
  // Kautham's ODE planners (physics-based): omplODE..., ...KPIECE2DPlanner, ...ChainPlanner.
  if (contains(name, "KnowledgeOriented"))
    return mapped(name, "o-KPIECE", "knowledge-oriented KPIECE over ODE");
  const bool physics = startsWith(name, "omplODE") || contains(name, "2DPlanner") ||
                       contains(name, "ChainPlanner") || contains(name, "CarPlanner");
  const bool control = startsWith(name, "omplc");
  if (physics || control) {
    const std::string what = physics ? "physics-based " : "control-based ";
    if (contains(name, "KPIECE")) return mapped(name, "KPIECE", what + "KPIECE");
    if (contains(name, "SST")) return mapped(name, "SST", what + "SST");
    if (contains(name, "PDST")) return mapped(name, "PDST", what + "PDST");
    if (contains(name, "EST")) return mapped(name, "EST", what + "EST");
    if (contains(name, "RRT")) return mapped(name, "RRT", what + "RRT");
  }
  if (startsWith(name, "ompl")) return geometric(name);
  return {KauthamPlanner::Kind::Unknown, "", ""};
}

std::optional<std::string> plannerToUse(const core::Problem& problem,
                                        const std::optional<std::string>& override, bool lenient) {
  if (override) return override;
  const KauthamPlanner kind = classifyPlanner(problem.planner.name);
  switch (kind.kind) {
    case KauthamPlanner::Kind::Ours:
    case KauthamPlanner::Kind::Unknown:  // the registry's message lists the known names
      return std::nullopt;
    case KauthamPlanner::Kind::Mapped:
      core::warning(problem.planner.nameWhere.str() + ": " + kind.note);
      return kind.planner;
    case KauthamPlanner::Kind::Geometric:
      if (!lenient) throw core::InputError(problem.planner.nameWhere, kind.note);
      core::warning(problem.planner.nameWhere.str() + ": " + kind.note + "; checked with '" +
                    kind.planner + "'");
      return kind.planner;
  }
  return std::nullopt;
}

}  // namespace kautham::apps

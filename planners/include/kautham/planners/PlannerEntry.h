#pragma once

// How a planner becomes a registry entry, with each parameter declared once:
//
// - a planner of ours (or a plugin's) has a settings struct and a core::SettingsParameters
//   table next to it; plannerEntry() lists the table's specs and fills the struct from the
//   values before the planner is built;
// - an OMPL planner keeps its settings in OMPL's own parameter set (Planner::params(), with
//   the names OMPL declares: goal_bias, border_fraction, range...); omplPlannerEntry() lists our
//   specs of them (defaults, ranges, descriptions, Kautham's aliases) and sets each by name.
//
// Either way the values also reach OMPL's declareParam (declareOmplParameters, called when
// `solve` makes the planner), so OMPL's tools record every parameter of every planner.

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <ompl/base/Planner.h>

#include "kautham/core/Parameter.h"
#include "kautham/planners/PlannerRegistry.h"

namespace kautham::planners {

/// The probability of expanding towards the goal: every planner here has one, with its own
/// default.
core::Parameter goalBiasParameter(double byDefault);

/// The side of the end-effector projection's cells as a fraction of the workspace side. A
/// planner that declares it gets the projection's cells set before it is built.
core::Parameter cellSizeParameter();

/// Applies the parameters the framework itself gives meaning to (cell_size) to the context.
void applyFrameworkParameters(const core::ParameterSet& values, physics::PlanningContext& context);

/// Sets the planner's OMPL parameters (Planner::params()) from the values of the same names,
/// exactly (every bit of a real). Throws std::logic_error for a value that is neither a
/// parameter the planner declares nor one of the framework's.
void setOmplParameters(ompl::base::Planner& planner, const core::ParameterSet& values);

/// Declares on the planner's OMPL parameter set every parameter of `values` the planner has
/// not declared itself, reading its value (and its range as OMPL's range suggestion). Setting
/// one of them through OMPL afterwards changes nothing and says so: they are fixed when the
/// planner is made.
void declareOmplParameters(ompl::base::Planner& planner, const core::ParameterSet& values);

/// Builds a planner from its filled settings and the planning context.
template <typename Settings>
using BuildFromSettings =
    std::function<ompl::base::PlannerPtr(const Settings&, physics::PlanningContext&)>;

/// The registry entry of a planner with a settings struct: its parameters are the table's,
/// and the struct is filled from the values by the table, field by field, before `build`.
template <typename Settings>
PlannerRegistry::Entry plannerEntry(std::string name, std::string summary,
                                    core::SettingsParameters<Settings> parameters,
                                    BuildFromSettings<Settings> build) {
  std::vector<core::ParameterSpec> specs = parameters.specs();
  return {std::move(name), std::move(summary), std::move(specs),
          [parameters = std::move(parameters), build = std::move(build)](
              const core::ParameterSet& values, physics::PlanningContext& context) {
            applyFrameworkParameters(values, context);
            return build(parameters.read(values), context);
          }};
}

/// The registry entry of an OMPL control planner over our physics (`OmplPlanner` is built
/// from the context's control SpaceInformation and named after the entry). `prepare` runs
/// first, before the framework's parameters: a planner that narrows the validity rules does
/// it there, because choosing rules sets the space information up again.
template <typename OmplPlanner>
PlannerRegistry::Entry omplPlannerEntry(
    std::string name, std::string summary, std::vector<core::ParameterSpec> parameters,
    std::function<void(physics::PlanningContext&)> prepare = nullptr) {
  return {name, std::move(summary), std::move(parameters),
          [name, prepare = std::move(prepare)](const core::ParameterSet& values,
                                               physics::PlanningContext& context) {
            if (prepare) prepare(context);
            applyFrameworkParameters(values, context);
            auto planner = std::make_shared<OmplPlanner>(context.spaceInformation());
            planner->setName(name);
            setOmplParameters(*planner, values);
            return ompl::base::PlannerPtr(planner);
          }};
}

}  // namespace kautham::planners

#pragma once

#include <ompl/geometric/planners/prm/PRM.h>

namespace kautham::planners::geometric {

/// OMPL's PRM that tries an edge from a new milestone only to neighbours in other connected
/// components of the roadmap, as Kautham's omplPRM does (its connection filter): an edge inside a
/// component adds no way the roadmap did not have, and each costs a collision-checked motion.
/// For a long arm on a mobile base checked at millimetres, those motions are nearly all of the
/// planning time.
class ComponentPRM : public ompl::geometric::PRM {
 public:
  explicit ComponentPRM(const ompl::base::SpaceInformationPtr& si);
};

}  // namespace kautham::planners::geometric

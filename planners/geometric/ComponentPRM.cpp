#include "kautham/planners/geometric/ComponentPRM.h"

namespace kautham::planners::geometric {

ComponentPRM::ComponentPRM(const ompl::base::SpaceInformationPtr& si) : ompl::geometric::PRM(si) {
  // OMPL asks the filter neighbour by neighbour, after the edges before it were added: once the
  // milestone joined a neighbour's component, the rest of that component is skipped.
  setConnectionFilter([this](const Vertex& neighbour, const Vertex& milestone) {
    return !sameComponent(neighbour, milestone);
  });
}

}  // namespace kautham::planners::geometric

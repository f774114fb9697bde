#include "kautham/planners/geometric/LinearLazyRRT.h"

#include <ompl/datastructures/NearestNeighborsLinear.h>

namespace kautham::planners::geometric {

LinearLazyRRT::LinearLazyRRT(const ompl::base::SpaceInformationPtr& si)
    : ompl::geometric::LazyRRT(si) {}

void LinearLazyRRT::setup() {
  // Before LazyRRT's own setup, which would otherwise choose OMPL's default.
  if (!nn_) nn_ = std::make_shared<ompl::NearestNeighborsLinear<Motion*>>();
  ompl::geometric::LazyRRT::setup();
}

}  // namespace kautham::planners::geometric

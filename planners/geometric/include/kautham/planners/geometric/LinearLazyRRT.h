#pragma once

#include <ompl/geometric/planners/rrt/LazyRRT.h>

namespace kautham::planners::geometric {

/// OMPL's LazyRRT over a linear nearest-neighbour structure. When a candidate path has an
/// invalid edge, LazyRRT removes every motion below it from that structure, and OMPL's default
/// (GNAT) rebuilds itself whenever a removed motion is one of its pivots: in Kautham's
/// S-passage, where nearly every candidate path hits a wall, 85 % of a run went to those
/// rebuilds and 0.3 % to collision checks. A linear structure removes an element in linear time
/// and never rebuilds.
class LinearLazyRRT : public ompl::geometric::LazyRRT {
 public:
  explicit LinearLazyRRT(const ompl::base::SpaceInformationPtr& si);
  void setup() override;
};

}  // namespace kautham::planners::geometric

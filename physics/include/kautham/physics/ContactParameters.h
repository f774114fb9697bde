#pragma once

namespace kautham::physics {

/// ODE's contact parameters, the paper's D = {mu, c, e}: sampled per particle around the
/// <Physics> block's values.
struct ContactParameters {
  double friction = 0.6;
  double erp = 0.2;
  double cfm = 1e-5;
};

}  // namespace kautham::physics

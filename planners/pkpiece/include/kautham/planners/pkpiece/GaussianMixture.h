#pragma once

#include <Eigen/Dense>
#include <random>
#include <vector>

namespace kautham::planners {

/// A planar object pose: (x, y) in metres, yaw in radians.
using PlanarPose = Eigen::Vector3d;

/// One Gaussian of a mixture over planar poses.
struct GaussianComponent {
  double weight = 1.0;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();  ///< (x, y, yaw), yaw in (-pi, pi]
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
};

/// Wraps an angle to (-pi, pi].
double wrapAngle(double angle);

/// A Gaussian mixture over planar poses (x, y, yaw), fitted by EM (p-KPIECE's U_rgn, paper
/// section IV-B, eq. 4). Yaw is an angle: each component is a normal distribution in the yaw
/// difference wrapped to (-pi, pi] around the component's mean, an approximation of a wrapped
/// normal that is accurate when the yaw spread is small compared with pi (see docs/gmm.md).
class GaussianMixture {
 public:
  struct FitOptions {
    int maxComponents = 3;           ///< BIC chooses among 1..maxComponents
    int minSamplesPerComponent = 3;  ///< at most samples / this many components
    int maxIterations = 100;         ///< EM iterations per run
    double tolerance = 1e-6;         ///< stop when the mean log-likelihood changes less
    int restarts = 3;                ///< EM runs (new seeding) per number of components
    Eigen::Vector3d minStdDev{1e-3, 1e-3, 1e-2};  ///< covariance floor: m, m, rad
  };

  /// Builds a mixture from components. Weights are normalised to sum 1; mean yaws are wrapped.
  /// Throws std::invalid_argument on no components, a negative or non-finite weight, a zero
  /// weight sum, a non-finite mean or a covariance that is not symmetric positive definite.
  explicit GaussianMixture(std::vector<GaussianComponent> components);

  /// Fits the outcome poses: the number of components is chosen by BIC among
  /// 1..min(options.maxComponents, samples / options.minSamplesPerComponent) (at least 1).
  /// Deterministic for a given rng state. Throws std::invalid_argument on empty samples,
  /// non-finite sample values or invalid options.
  static GaussianMixture fit(const std::vector<PlanarPose>& samples, const FitOptions& options,
                             std::mt19937_64& rng);
  static GaussianMixture fit(const std::vector<PlanarPose>& samples, std::mt19937_64& rng);

  /// One Gaussian (the initial uncertainty U_init): stddevs must be finite and positive.
  static GaussianMixture single(const PlanarPose& mean, const Eigen::Vector3d& stddevs);

  /// Draws a pose; yaw wrapped to (-pi, pi]. Uses only rng() (no std distributions), so the
  /// draws do not depend on the standard library's distribution implementations.
  PlanarPose sample(std::mt19937_64& rng) const;

  /// Log of the mixture density at pose (yaw difference wrapped around each component mean).
  double logDensity(const PlanarPose& pose) const;

  /// Sum of logDensity over the samples.
  double logLikelihood(const std::vector<PlanarPose>& samples) const;

  /// Bayesian information criterion: -2 log L + p ln n, p = 10 k - 1 free parameters
  /// (k - 1 weights, 3 k means, 6 k covariance entries). Lower is better.
  double bic(const std::vector<PlanarPose>& samples) const;

  const std::vector<GaussianComponent>& components() const { return components_; }

 private:
  struct Cache {
    Eigen::Matrix3d choleskyL;  ///< covariance = L L^T
    double logNormaliser;       ///< log weight - 1.5 log(2 pi) - log det(L)
  };

  /// log(weight_j) + log N_j(pose).
  double weightedLogDensity(std::size_t j, const PlanarPose& pose) const;

  std::vector<GaussianComponent> components_;
  std::vector<Cache> cache_;
};

}  // namespace kautham::planners

#include "kautham/planners/pkpiece/GaussianMixture.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

// Yaw wrap-around. The mixture lives on R^2 x S^1. Each component is treated as a normal
// distribution in (dx, dy, wrap(yaw - mean_yaw)): the E-step and logDensity use the yaw
// difference wrapped to (-pi, pi] relative to the component mean, the M-step takes the
// weighted circular mean of yaw (atan2 of the weighted sin and cos sums) and the covariance
// from the wrapped differences. This approximates a wrapped normal and is accurate when the
// component's yaw spread is small compared with pi (the density is then normalised to within
// the tail mass beyond +-pi), which is the case for object poses after a push.

namespace kautham::planners {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kLog2Pi = 1.83787706640934548356;  // log(2 pi)

// Uniform in [0, 1) from 53 random bits: portable, unlike std::uniform_real_distribution.
double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// Standard normal by Box-Muller: portable, unlike std::normal_distribution.
std::pair<double, double> normalPair(std::mt19937_64& rng) {
  const double u1 = 1.0 - uniform01(rng);  // (0, 1]
  const double u2 = uniform01(rng);
  const double r = std::sqrt(-2.0 * std::log(u1));
  return {r * std::cos(2.0 * kPi * u2), r * std::sin(2.0 * kPi * u2)};
}

// The difference pose - mean with the yaw difference wrapped to (-pi, pi].
Eigen::Vector3d difference(const PlanarPose& pose, const Eigen::Vector3d& mean) {
  return {pose.x() - mean.x(), pose.y() - mean.y(), wrapAngle(pose.z() - mean.z())};
}

// Floors the covariance so that its standard deviation along every axis, and in every
// direction measured in floor units, is at least the floor: with D = diag(minStdDev), the
// eigenvalues of D^-1 C D^-1 are clamped to >= 1. A zero covariance (identical samples, a
// single sample) becomes exactly D^2; a well-spread covariance is unchanged.
Eigen::Matrix3d floorCovariance(const Eigen::Matrix3d& covariance,
                                const Eigen::Vector3d& minStdDev) {
  const Eigen::Vector3d inverse = minStdDev.cwiseInverse();
  Eigen::Matrix3d scaled = inverse.asDiagonal() * covariance * inverse.asDiagonal();
  scaled = 0.5 * (scaled + scaled.transpose()).eval();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(scaled);
  const Eigen::Vector3d clamped = eigen.eigenvalues().cwiseMax(1.0);
  Eigen::Matrix3d result = minStdDev.asDiagonal() * eigen.eigenvectors() * clamped.asDiagonal() *
                           eigen.eigenvectors().transpose() * minStdDev.asDiagonal();
  return 0.5 * (result + result.transpose());
}

// The samples' yaws on the unit circle, worked out once per fit: every M-step of every EM run
// takes weighted sums of them.
struct YawCircle {
  std::vector<double> sines, cosines;
  explicit YawCircle(const std::vector<PlanarPose>& samples) {
    for (const PlanarPose& s : samples) {
      sines.push_back(std::sin(s.z()));
      cosines.push_back(std::cos(s.z()));
    }
  }
};

// Weighted mean (circular for yaw) and floored covariance of the samples.
GaussianComponent weightedComponent(const std::vector<PlanarPose>& samples, const YawCircle& yaw,
                                    const Eigen::VectorXd& weights,
                                    const Eigen::Vector3d& minStdDev) {
  const double total = weights.sum();
  GaussianComponent component;
  double sumX = 0.0, sumY = 0.0, sumSin = 0.0, sumCos = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const double w = weights[static_cast<Eigen::Index>(i)];
    sumX += w * samples[i].x();
    sumY += w * samples[i].y();
    sumSin += w * yaw.sines[i];
    sumCos += w * yaw.cosines[i];
  }
  component.mean = {sumX / total, sumY / total, wrapAngle(std::atan2(sumSin, sumCos))};
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const Eigen::Vector3d d = difference(samples[i], component.mean);
    covariance += weights[static_cast<Eigen::Index>(i)] * d * d.transpose();
  }
  component.covariance = floorCovariance(covariance / total, minStdDev);
  component.weight = total;
  return component;
}

// Squared distance in units of the per-axis scale, yaw wrapped (k-means++ seeding).
double scaledDistance2(const PlanarPose& a, const PlanarPose& b, const Eigen::Vector3d& scale) {
  return difference(a, b).cwiseQuotient(scale).squaredNorm();
}

// k-means++ seeding: the first seed uniformly, each next one with probability proportional to
// its squared scaled distance to the nearest seed chosen so far.
std::vector<PlanarPose> seeds(const std::vector<PlanarPose>& samples, int k,
                              const Eigen::Vector3d& scale, std::mt19937_64& rng) {
  const std::size_t n = samples.size();
  const auto uniformIndex = [&] {
    return std::min(n - 1, static_cast<std::size_t>(uniform01(rng) * static_cast<double>(n)));
  };
  std::vector<PlanarPose> chosen{samples[uniformIndex()]};
  std::vector<double> nearest(n, std::numeric_limits<double>::infinity());
  while (static_cast<int>(chosen.size()) < k) {
    double total = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      nearest[i] = std::min(nearest[i], scaledDistance2(samples[i], chosen.back(), scale));
      total += nearest[i];
    }
    std::size_t pick = 0;
    if (total <= 0.0) {
      pick = uniformIndex();  // all samples coincide with the seeds
    } else {
      const double target = uniform01(rng) * total;
      double cumulative = 0.0;
      pick = n - 1;
      for (std::size_t i = 0; i < n; ++i) {
        cumulative += nearest[i];
        if (cumulative > target && nearest[i] > 0.0) {
          pick = i;
          break;
        }
      }
    }
    chosen.push_back(samples[pick]);
  }
  return chosen;
}

// One EM run with k components from a k-means++ seeding. Components whose responsibility
// vanishes are dropped, so the result may have fewer than k components.
GaussianMixture runEm(const std::vector<PlanarPose>& samples, const YawCircle& yaw, int k,
                      const GaussianComponent& global, const Eigen::Vector3d& scale,
                      const GaussianMixture::FitOptions& options, std::mt19937_64& rng) {
  const std::size_t n = samples.size();
  std::vector<GaussianComponent> components;
  for (const PlanarPose& seed : seeds(samples, k, scale, rng)) {
    components.push_back({1.0 / k, seed, global.covariance});
  }
  double previous = -std::numeric_limits<double>::infinity();
  for (int iteration = 0; iteration < options.maxIterations; ++iteration) {
    const GaussianMixture mixture(components);
    const std::size_t m = mixture.components().size();
    // E-step with log-sum-exp: responsibilities r(i, j) and the log-likelihood.
    std::vector<Eigen::LLT<Eigen::Matrix3d>> factors;
    std::vector<double> logNormalisers;  // log weight - 0.5 (3 log 2 pi + log det)
    for (const GaussianComponent& c : mixture.components()) {
      factors.emplace_back(c.covariance);
      logNormalisers.push_back(std::log(c.weight) - 1.5 * kLog2Pi -
                               factors.back().matrixLLT().diagonal().array().log().sum());
    }
    Eigen::MatrixXd responsibility(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(m));
    double logLikelihood = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const auto row = static_cast<Eigen::Index>(i);
      for (std::size_t j = 0; j < m; ++j) {
        const Eigen::Vector3d d = difference(samples[i], mixture.components()[j].mean);
        const Eigen::Vector3d z = factors[j].matrixL().solve(d);
        responsibility(row, static_cast<Eigen::Index>(j)) =
            logNormalisers[j] - 0.5 * z.squaredNorm();
      }
      const double maximum = responsibility.row(row).maxCoeff();
      const double logSum =
          maximum + std::log((responsibility.row(row).array() - maximum).exp().sum());
      responsibility.row(row) = (responsibility.row(row).array() - logSum).exp();
      logLikelihood += logSum;
    }
    const double change = logLikelihood - previous;
    previous = logLikelihood;
    if (std::abs(change) < options.tolerance * static_cast<double>(n)) break;
    // M-step.
    components.clear();
    for (std::size_t j = 0; j < m; ++j) {
      const Eigen::VectorXd column = responsibility.col(static_cast<Eigen::Index>(j));
      if (column.sum() < 1e-8) continue;  // an empty component: drop it
      GaussianComponent c = weightedComponent(samples, yaw, column, options.minStdDev);
      c.weight /= static_cast<double>(n);
      components.push_back(c);
    }
  }
  return GaussianMixture(components);
}

void checkSamples(const std::vector<PlanarPose>& samples) {
  if (samples.empty()) {
    throw std::invalid_argument("GaussianMixture: no samples to fit (need at least one pose)");
  }
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (!samples[i].allFinite()) {
      throw std::invalid_argument("GaussianMixture: sample " + std::to_string(i) +
                                  " has a NaN or infinite coordinate");
    }
  }
}

}  // namespace

double wrapAngle(double angle) {
  // Within a turn and a quarter either way (the differences of two wrapped yaws, which EM asks
  // for per sample and component) one turn is added or taken away; the result is then the
  // exact remainder, as std::remainder's is, so both give the same bits, and this is cheaper.
  double wrapped;
  if (angle >= -kPi && angle <= kPi)
    wrapped = angle;
  else if (angle > kPi && angle < 2.5 * kPi)
    wrapped = angle - 2.0 * kPi;
  else if (angle < -kPi && angle > -2.5 * kPi)
    wrapped = angle + 2.0 * kPi;
  else
    wrapped = std::remainder(angle, 2.0 * kPi);  // [-pi, pi]
  if (wrapped <= -kPi) wrapped += 2.0 * kPi;
  return wrapped;
}

GaussianMixture::GaussianMixture(std::vector<GaussianComponent> components)
    : components_(std::move(components)) {
  if (components_.empty()) throw std::invalid_argument("GaussianMixture: no components");
  double total = 0.0;
  for (const GaussianComponent& c : components_) {
    if (!std::isfinite(c.weight) || c.weight < 0.0) {
      throw std::invalid_argument("GaussianMixture: component weight must be finite and >= 0");
    }
    total += c.weight;
  }
  if (!(total > 0.0)) throw std::invalid_argument("GaussianMixture: weights sum to zero");
  for (GaussianComponent& c : components_) {
    if (!c.mean.allFinite() || !c.covariance.allFinite()) {
      throw std::invalid_argument("GaussianMixture: non-finite component mean or covariance");
    }
    if (!c.covariance.isApprox(c.covariance.transpose(), 1e-9)) {
      throw std::invalid_argument("GaussianMixture: component covariance is not symmetric");
    }
    const Eigen::LLT<Eigen::Matrix3d> llt(c.covariance);
    if (llt.info() != Eigen::Success || !(llt.matrixLLT().diagonal().array() > 0.0).all()) {
      throw std::invalid_argument("GaussianMixture: component covariance is not positive definite");
    }
    c.weight /= total;
    c.mean.z() = wrapAngle(c.mean.z());
    Cache cache;
    cache.choleskyL = llt.matrixL();
    cache.logNormaliser =
        std::log(c.weight) - 1.5 * kLog2Pi - cache.choleskyL.diagonal().array().log().sum();
    cache_.push_back(cache);
  }
}

GaussianMixture GaussianMixture::fit(const std::vector<PlanarPose>& samples, std::mt19937_64& rng) {
  return fit(samples, FitOptions{}, rng);
}

GaussianMixture GaussianMixture::fit(const std::vector<PlanarPose>& samples,
                                     const FitOptions& options, std::mt19937_64& rng) {
  checkSamples(samples);
  if (options.maxComponents < 1 || options.minSamplesPerComponent < 1 ||
      options.maxIterations < 1 || options.restarts < 1 || !(options.tolerance >= 0.0) ||
      !options.minStdDev.allFinite() || !(options.minStdDev.array() > 0.0).all()) {
    throw std::invalid_argument(
        "GaussianMixture::fit: maxComponents, minSamplesPerComponent, maxIterations and "
        "restarts must be >= 1, tolerance >= 0 and minStdDev finite and > 0");
  }
  const int n = static_cast<int>(samples.size());
  const int maxComponents =
      std::max(1, std::min(options.maxComponents, n / options.minSamplesPerComponent));

  const YawCircle yaw(samples);
  // One component: closed form (EM converges in one step).
  const GaussianComponent global =
      weightedComponent(samples, yaw, Eigen::VectorXd::Ones(n), options.minStdDev);
  GaussianMixture best({{1.0, global.mean, global.covariance}});
  double bestBic = best.bic(samples);

  // Seeding distances in units of the overall spread (at least the floor) per axis.
  const Eigen::Vector3d scale =
      global.covariance.diagonal().cwiseSqrt().cwiseMax(options.minStdDev);
  for (int k = 2; k <= maxComponents; ++k) {
    for (int run = 0; run < options.restarts; ++run) {
      GaussianMixture candidate = runEm(samples, yaw, k, global, scale, options, rng);
      const double candidateBic = candidate.bic(samples);
      if (candidateBic < bestBic) {  // strict: ties keep fewer components
        best = std::move(candidate);
        bestBic = candidateBic;
      }
    }
  }
  return best;
}

GaussianMixture GaussianMixture::single(const PlanarPose& mean, const Eigen::Vector3d& stddevs) {
  if (!mean.allFinite() || !stddevs.allFinite() || !(stddevs.array() > 0.0).all()) {
    throw std::invalid_argument(
        "GaussianMixture::single: mean must be finite and standard deviations finite and > 0");
  }
  return GaussianMixture({{1.0, mean, stddevs.cwiseAbs2().asDiagonal().toDenseMatrix()}});
}

PlanarPose GaussianMixture::sample(std::mt19937_64& rng) const {
  const double u = uniform01(rng);
  std::size_t j = 0;
  double cumulative = components_[0].weight;
  while (j + 1 < components_.size() && u >= cumulative) cumulative += components_[++j].weight;
  const auto [z0, z1] = normalPair(rng);
  const auto [z2, unused] = normalPair(rng);
  (void)unused;
  PlanarPose pose = components_[j].mean + cache_[j].choleskyL * Eigen::Vector3d(z0, z1, z2);
  pose.z() = wrapAngle(pose.z());
  return pose;
}

double GaussianMixture::weightedLogDensity(std::size_t j, const PlanarPose& pose) const {
  const Eigen::Vector3d z = cache_[j].choleskyL.triangularView<Eigen::Lower>().solve(
      difference(pose, components_[j].mean));
  return cache_[j].logNormaliser - 0.5 * z.squaredNorm();
}

double GaussianMixture::logDensity(const PlanarPose& pose) const {
  double maximum = -std::numeric_limits<double>::infinity();
  std::vector<double> terms(components_.size());
  for (std::size_t j = 0; j < components_.size(); ++j) {
    terms[j] = weightedLogDensity(j, pose);
    maximum = std::max(maximum, terms[j]);
  }
  if (!std::isfinite(maximum)) return maximum;
  double sum = 0.0;
  for (double t : terms) sum += std::exp(t - maximum);
  return maximum + std::log(sum);
}

double GaussianMixture::logLikelihood(const std::vector<PlanarPose>& samples) const {
  double total = 0.0;
  for (const PlanarPose& pose : samples) total += logDensity(pose);
  return total;
}

double GaussianMixture::bic(const std::vector<PlanarPose>& samples) const {
  checkSamples(samples);
  const double parameters = 10.0 * static_cast<double>(components_.size()) - 1.0;
  return -2.0 * logLikelihood(samples) + parameters * std::log(static_cast<double>(samples.size()));
}

}  // namespace kautham::planners

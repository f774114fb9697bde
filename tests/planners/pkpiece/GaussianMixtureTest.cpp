#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "kautham/planners/pkpiece/GaussianMixture.h"

namespace kautham::planners {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Draws n poses from a known mixture (yaw not wrapped: the test mixtures stay away from pi).
std::vector<PlanarPose> draw(const std::vector<GaussianComponent>& truth, int n,
                             std::mt19937_64& rng) {
  std::discrete_distribution<int> pick({truth[0].weight, truth.size() > 1 ? truth[1].weight : 0.0,
                                        truth.size() > 2 ? truth[2].weight : 0.0});
  std::normal_distribution<double> normal;
  std::vector<PlanarPose> samples;
  for (int i = 0; i < n; ++i) {
    const GaussianComponent& c = truth[static_cast<std::size_t>(pick(rng))];
    const Eigen::Matrix3d l = c.covariance.llt().matrixL();
    samples.push_back(c.mean + l * Eigen::Vector3d(normal(rng), normal(rng), normal(rng)));
  }
  return samples;
}

// The fitted component whose mean is nearest (x, y) to the given one.
const GaussianComponent& nearest(const GaussianMixture& gmm, const Eigen::Vector3d& mean) {
  const GaussianComponent* best = &gmm.components().front();
  for (const GaussianComponent& c : gmm.components()) {
    if ((c.mean - mean).head<2>().norm() < (best->mean - mean).head<2>().norm()) best = &c;
  }
  return *best;
}

Eigen::Matrix3d covariance(double sx, double sy, double syaw, double rhoXY = 0.0) {
  Eigen::Matrix3d c = Eigen::Vector3d(sx * sx, sy * sy, syaw * syaw).asDiagonal();
  c(0, 1) = c(1, 0) = rhoXY * sx * sy;
  return c;
}

const std::vector<GaussianComponent> kTwo = {
    {0.3, {0.10, 0.20, 0.5}, covariance(0.01, 0.02, 0.05, 0.5)},
    {0.7, {0.30, -0.10, -0.8}, covariance(0.02, 0.01, 0.10, -0.3)},
};

TEST(GaussianMixtureTest, RecoversKnownTwoComponentMixture) {
  std::mt19937_64 rng(42);
  const std::vector<PlanarPose> samples = draw(kTwo, 400, rng);
  const GaussianMixture gmm = GaussianMixture::fit(samples, rng);
  ASSERT_EQ(gmm.components().size(), 2u);
  for (const GaussianComponent& truth : kTwo) {
    const GaussianComponent& fitted = nearest(gmm, truth.mean);
    EXPECT_NEAR(fitted.weight, truth.weight, 0.07);
    const Eigen::Vector3d standardError =
        (truth.covariance.diagonal() / (400.0 * truth.weight)).cwiseSqrt();
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(fitted.mean[a], truth.mean[a], 4.0 * standardError[a]) << "axis " << a;
      EXPECT_NEAR(fitted.covariance(a, a), truth.covariance(a, a), 0.35 * truth.covariance(a, a))
          << "axis " << a;
    }
  }
  double weights = 0.0;
  for (const GaussianComponent& c : gmm.components()) weights += c.weight;
  EXPECT_NEAR(weights, 1.0, 1e-12);
}

TEST(GaussianMixtureTest, SingleGaussianGivesOneComponent) {
  std::mt19937_64 rng(7);
  const std::vector<GaussianComponent> one = {
      {1.0, {0.5, 0.4, 1.0}, covariance(0.03, 0.01, 0.2, 0.8)}};
  const std::vector<PlanarPose> samples = draw(one, 300, rng);
  const GaussianMixture gmm = GaussianMixture::fit(samples, rng);
  ASSERT_EQ(gmm.components().size(), 1u);
  EXPECT_TRUE(gmm.components()[0].mean.isApprox(one[0].mean, 0.02));
  EXPECT_NEAR(gmm.components()[0].covariance(0, 1), one[0].covariance(0, 1), 0.3e-4);
}

TEST(GaussianMixtureTest, ThreeSeparatedClustersGiveThreeComponents) {
  std::mt19937_64 rng(3);
  const std::vector<GaussianComponent> three = {
      {0.3, {0.0, 0.0, 0.0}, covariance(0.01, 0.01, 0.05)},
      {0.3, {0.2, 0.0, 1.0}, covariance(0.01, 0.02, 0.05)},
      {0.4, {0.1, 0.2, -1.0}, covariance(0.02, 0.01, 0.1)},
  };
  const std::vector<PlanarPose> samples = draw(three, 300, rng);
  const GaussianMixture gmm = GaussianMixture::fit(samples, rng);
  ASSERT_EQ(gmm.components().size(), 3u);
  for (const GaussianComponent& truth : three) {
    EXPECT_NEAR(nearest(gmm, truth.mean).weight, truth.weight, 0.07);
    EXPECT_LT((nearest(gmm, truth.mean).mean - truth.mean).head<2>().norm(), 0.01);
  }
}

TEST(GaussianMixtureTest, TypicalParticleCountsFitAndNeverExceedSamplesPerComponent) {
  std::mt19937_64 rng(11);
  const std::vector<PlanarPose> samples = draw(kTwo, 20, rng);
  const GaussianMixture gmm = GaussianMixture::fit(samples, rng);
  EXPECT_GE(gmm.components().size(), 1u);
  EXPECT_LE(gmm.components().size(), 3u);
  // Five samples of two clusters: 5 / 3 allows one component only.
  const std::vector<PlanarPose> few = {
      {0, 0, 0}, {0.001, 0, 0}, {0, 0.001, 0}, {1, 1, 1}, {1.001, 1, 1}};
  EXPECT_EQ(GaussianMixture::fit(few, rng).components().size(), 1u);
}

TEST(GaussianMixtureTest, YawAroundPiIsOneComponentWithSmallSpread) {
  // One cluster of yaw about pi, std 0.05 rad: wrapped, about half the samples are near +3.1
  // and half near -3.1 (alternating signs). A fit on raw yaw would see two clusters (or one with
  // std ~3 about 0).
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0.0, 0.05);
  std::vector<PlanarPose> samples;
  int positive = 0;
  for (int i = 0; i < 40; ++i) {
    const double offset = std::abs(noise(rng)) * (i % 2 == 0 ? 1.0 : -1.0);  // symmetric
    const double yaw = wrapAngle(kPi + offset);
    positive += yaw > 0.0 ? 1 : 0;
    samples.push_back({0.3 + noise(rng) / 5, 0.1 + noise(rng) / 5, yaw});
  }
  ASSERT_EQ(positive, 20);
  const GaussianMixture gmm = GaussianMixture::fit(samples, rng);
  ASSERT_EQ(gmm.components().size(), 1u);
  const GaussianComponent& c = gmm.components()[0];
  EXPECT_GT(c.mean.z(), -kPi);
  EXPECT_LE(c.mean.z(), kPi);
  EXPECT_NEAR(std::abs(c.mean.z()), kPi, 0.03);
  EXPECT_LT(std::sqrt(c.covariance(2, 2)), 0.1);  // not ~3.1 around 0
  // The density is continuous across the wrap.
  EXPECT_NEAR(gmm.logDensity({0.3, 0.1, kPi}), gmm.logDensity({0.3, 0.1, -kPi}), 1e-9);
  // Sampling wraps yaw into (-pi, pi].
  for (int i = 0; i < 1000; ++i) {
    const PlanarPose pose = gmm.sample(rng);
    EXPECT_GT(pose.z(), -kPi);
    EXPECT_LE(pose.z(), kPi);
  }
}

TEST(GaussianMixtureTest, WrapAngleIsTheExactRemainderToTheBit) {
  // The cheap branches must give what std::remainder gives, or plans would change in their
  // last bits: near the branch limits, at +-pi, and far out where the remainder is still used.
  const auto byRemainder = [](double angle) {
    double wrapped = std::remainder(angle, 2.0 * kPi);
    if (wrapped <= -kPi) wrapped += 2.0 * kPi;
    return wrapped;
  };
  std::vector<double> angles = {0.0,        kPi,       -kPi,       2.0 * kPi, -2.0 * kPi, 2.5 * kPi,
                                -2.5 * kPi, 3.0 * kPi, -3.0 * kPi, 1e3,       -1e3};
  for (double a : {kPi, 2.5 * kPi, 3.0 * kPi})
    for (double sign : {1.0, -1.0}) {
      angles.push_back(std::nextafter(sign * a, 0.0));
      angles.push_back(std::nextafter(sign * a, sign * 10.0));
    }
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> any(-4.0 * kPi, 4.0 * kPi);
  for (int i = 0; i < 100000; ++i) angles.push_back(any(rng));
  for (double a : angles) EXPECT_EQ(wrapAngle(a), byRemainder(a)) << a;
  EXPECT_TRUE(std::isnan(wrapAngle(std::numeric_limits<double>::quiet_NaN())));
}

TEST(GaussianMixtureTest, IdenticalOrSingleSamplesGetTheFloorCovariance) {
  std::mt19937_64 rng(1);
  GaussianMixture::FitOptions options;
  const Eigen::Matrix3d floor = options.minStdDev.cwiseAbs2().asDiagonal();
  const PlanarPose pose(0.4, -0.2, 2.0);
  for (std::size_t n : {std::size_t{1}, std::size_t{30}}) {
    const GaussianMixture gmm =
        GaussianMixture::fit(std::vector<PlanarPose>(n, pose), options, rng);
    ASSERT_EQ(gmm.components().size(), 1u) << n;
    const GaussianComponent& c = gmm.components()[0];
    EXPECT_TRUE(c.covariance.allFinite());
    EXPECT_TRUE(c.mean.isApprox(pose, 1e-12)) << n;
    EXPECT_LT((c.covariance - floor).norm(), 1e-12 * floor.norm()) << n;
    EXPECT_TRUE(std::isfinite(gmm.logDensity(pose)));
  }
}

TEST(GaussianMixtureTest, CovarianceFloorHoldsPerAxis) {
  std::mt19937_64 rng(2);
  // Spread in x only: y and yaw are degenerate and must be floored, x kept.
  std::vector<PlanarPose> samples;
  for (int i = 0; i < 20; ++i) samples.push_back({0.01 * i, 0.5, 0.0});
  const GaussianMixture gmm = GaussianMixture::fit(samples, rng);
  for (const GaussianComponent& c : gmm.components()) {
    EXPECT_GE(c.covariance(1, 1), 1e-6 * (1 - 1e-9));
    EXPECT_GE(c.covariance(2, 2), 1e-4 * (1 - 1e-9));
    EXPECT_EQ(c.covariance.llt().info(), Eigen::Success);
  }
}

TEST(GaussianMixtureTest, SameSeedGivesIdenticalFit) {
  std::mt19937_64 dataRng(9);
  const std::vector<PlanarPose> samples = draw(kTwo, 30, dataRng);
  std::mt19937_64 a(123), b(123);
  const GaussianMixture first = GaussianMixture::fit(samples, a);
  const GaussianMixture second = GaussianMixture::fit(samples, b);
  ASSERT_EQ(first.components().size(), second.components().size());
  for (std::size_t j = 0; j < first.components().size(); ++j) {
    EXPECT_EQ(first.components()[j].weight, second.components()[j].weight);
    EXPECT_EQ(first.components()[j].mean, second.components()[j].mean);
    EXPECT_EQ(first.components()[j].covariance, second.components()[j].covariance);
  }
  EXPECT_EQ(a(), b());  // the same amount of randomness was used
  EXPECT_EQ(first.sample(a), second.sample(b));
}

TEST(GaussianMixtureTest, SamplingReproducesTheMixtureMoments) {
  const GaussianMixture gmm(kTwo);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const GaussianComponent& c : gmm.components()) mean += c.weight * c.mean;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const GaussianComponent& c : gmm.components()) {
    cov += c.weight * (c.covariance + (c.mean - mean) * (c.mean - mean).transpose());
  }
  std::mt19937_64 rng(17);
  const int n = 5000;
  std::vector<PlanarPose> draws;
  for (int i = 0; i < n; ++i) draws.push_back(gmm.sample(rng));
  Eigen::Vector3d sampleMean = Eigen::Vector3d::Zero();
  for (const PlanarPose& p : draws) sampleMean += p / n;
  Eigen::Matrix3d sampleCov = Eigen::Matrix3d::Zero();
  for (const PlanarPose& p : draws) {
    sampleCov += (p - sampleMean) * (p - sampleMean).transpose() / (n - 1);
  }
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(sampleMean[a], mean[a], 4.0 * std::sqrt(cov(a, a) / n)) << a;
    for (int b = 0; b < 3; ++b) {
      EXPECT_NEAR(sampleCov(a, b), cov(a, b), 0.1 * std::sqrt(cov(a, a) * cov(b, b))) << a << b;
    }
  }
}

TEST(GaussianMixtureTest, LogDensityIsANormalisedDensity) {
  const GaussianMixture single = GaussianMixture::single({0.1, 0.2, 0.3}, {0.01, 0.02, 0.1});
  const double atMean = single.logDensity({0.1, 0.2, 0.3});
  EXPECT_NEAR(atMean, -1.5 * std::log(2 * kPi) - std::log(0.01 * 0.02 * 0.1), 1e-9);
  EXPECT_NEAR(single.logDensity({0.13, 0.2, 0.3}), atMean - 4.5, 1e-9);  // 3 sigma in x
  EXPECT_GT(atMean, single.logDensity({0.1, 0.2, 0.6}));

  // A midpoint-rule integral of the two-component density over a box holding both.
  const GaussianMixture gmm(kTwo);
  const Eigen::Vector3d lo(0.0, -0.2, -1.6), hi(0.45, 0.35, 1.0);
  const int cells = 60;
  const Eigen::Vector3d h = (hi - lo) / cells;
  double integral = 0.0;
  for (int i = 0; i < cells; ++i) {
    for (int j = 0; j < cells; ++j) {
      for (int k = 0; k < cells; ++k) {
        const Eigen::Vector3d p = lo + Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5).cwiseProduct(h);
        integral += std::exp(gmm.logDensity(p));
      }
    }
  }
  EXPECT_NEAR(integral * h.prod(), 1.0, 0.01);
}

TEST(GaussianMixtureTest, BicPrefersTheTrueNumberOfComponents) {
  std::mt19937_64 rng(21);
  const std::vector<PlanarPose> samples = draw(kTwo, 200, rng);
  const GaussianMixture truth(kTwo);
  const GaussianMixture one =
      GaussianMixture::single({0.24, 0.0, -0.4}, {0.1, 0.15, 0.6});  // a broad single
  EXPECT_LT(truth.bic(samples), one.bic(samples));
}

TEST(GaussianMixtureTest, InvalidInputsThrow) {
  std::mt19937_64 rng(0);
  EXPECT_THROW(GaussianMixture::fit({}, rng), std::invalid_argument);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(GaussianMixture::fit({{0, 0, 0}, {nan, 0, 0}}, rng), std::invalid_argument);
  EXPECT_THROW(GaussianMixture::fit({{0, 0, inf}}, rng), std::invalid_argument);
  GaussianMixture::FitOptions options;
  options.maxComponents = 0;
  EXPECT_THROW(GaussianMixture::fit({{0, 0, 0}}, options, rng), std::invalid_argument);
  options = {};
  options.minStdDev.z() = 0.0;
  EXPECT_THROW(GaussianMixture::fit({{0, 0, 0}}, options, rng), std::invalid_argument);
  EXPECT_THROW(GaussianMixture::single({0, 0, 0}, {0.01, 0.0, 0.1}), std::invalid_argument);
  EXPECT_THROW(GaussianMixture(std::vector<GaussianComponent>{}), std::invalid_argument);
  EXPECT_THROW(GaussianMixture({{1.0, {0, 0, 0}, Eigen::Matrix3d::Zero()}}), std::invalid_argument);
  EXPECT_THROW(GaussianMixture({{-1.0, {0, 0, 0}, Eigen::Matrix3d::Identity()}}),
               std::invalid_argument);
  EXPECT_THROW(GaussianMixture::single({0, 0, 0}, {1, 1, 1}).bic({}), std::invalid_argument);
}

}  // namespace
}  // namespace kautham::planners

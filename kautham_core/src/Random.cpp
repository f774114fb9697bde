#include "kautham/core/Random.h"

#include <cmath>
#include <cstdint>

namespace kautham::core {

double uniform01(std::mt19937_64& rng) {
  constexpr double kUnit = 1.0 / 9007199254740992.0;  // 2^-53
  const std::uint64_t bits = rng() >> 11;             // 53 bits: exact in a double
  return (static_cast<double>(bits) + 0.5) * kUnit;
}

double standardNormal(std::mt19937_64& rng) {
  const double u1 = uniform01(rng);  // in (0, 1): the logarithm is finite
  const double u2 = uniform01(rng);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
}

std::uint64_t mix64(std::uint64_t x) {
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

namespace {

std::uint64_t splitMix64(std::uint64_t x) { return mix64(x + 0x9E3779B97F4A7C15ULL); }

}  // namespace

std::uint64_t runSeed(std::uint64_t seed, std::uint64_t index) {
  return splitMix64(splitMix64(seed) ^ splitMix64(index + 0x5851F42D4C957F2DULL));
}

}  // namespace kautham::core

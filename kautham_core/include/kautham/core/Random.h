#pragma once

// Random numbers computed from std::mt19937_64's raw output only. The standard distributions
// (std::uniform_real_distribution, std::normal_distribution) are implementation-defined, so
// the same seed gives different numbers with libstdc++ and libc++; these give the same
// numbers everywhere, which makes seeded runs (`kautham validate --seed`) reproducible.

#include <cstdint>
#include <random>

namespace kautham::core {

/// A uniform number in the open interval (0, 1): the top 53 bits of one raw draw, offset by
/// half a unit so that neither 0 nor 1 can occur. Consumes exactly one raw draw.
double uniform01(std::mt19937_64& rng);

/// A standard normal number (mean 0, variance 1) by the Box-Muller transform. The second
/// number of the pair is not cached, so every call consumes exactly two raw draws.
double standardNormal(std::mt19937_64& rng);

/// The seed of the `index`-th of several independent streams derived from one seed (SplitMix64
/// mixing): run i of `kautham validate --seed S` uses std::mt19937_64(runSeed(S, i)), so each
/// run's numbers depend on S and i only, not on the order the runs are made in.
std::uint64_t runSeed(std::uint64_t seed, std::uint64_t index);

/// SplitMix64's finaliser: 64 well-mixed bits from `x`, for a value drawn from a key (a hash)
/// rather than from a stream.
std::uint64_t mix64(std::uint64_t x);

}  // namespace kautham::core

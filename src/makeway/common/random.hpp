#pragma once
// Seeded random numbers. Every random process in makeway takes a seed; the same seed gives the
// same output bit for bit (the distributions below are written out, not left to the standard
// library, whose distributions differ between implementations).
#include <cstdint>
#include <random>
#include <utility>

namespace makeway {

using Rng = std::mt19937_64;

/// Generator for one named stream of a seeded process: the same (seed, stream) pair always gives
/// the same sequence, and different streams are decorrelated (SplitMix64 seeding).
Rng make_rng(std::uint64_t seed, std::uint64_t stream = 0);

/// Uniform in [lo, hi).
double uniform(Rng& rng, double lo, double hi);
/// Normal with the given mean and standard deviation (Box-Muller).
double normal(Rng& rng, double mean, double stddev);
/// Uniform integer in [lo, hi] (inclusive).
std::int64_t uniform_int(Rng& rng, std::int64_t lo, std::int64_t hi);
/// True with probability p.
bool bernoulli(Rng& rng, double p);

/// Counter-based draws: a pure function of (seed, counter), so parallel loops give the same values
/// as serial ones whatever the thread schedule. Uniform in [0, 1).
double counter_uniform(std::uint64_t seed, std::uint64_t counter);
/// Two independent standard normals for one (seed, counter) (Marsaglia's polar method: no
/// trigonometry, one logarithm per pair); the cheap path for per-ray sensor noise.
std::pair<double, double> counter_normal_pair(std::uint64_t seed, std::uint64_t counter);

}  // namespace makeway

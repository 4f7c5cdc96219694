#include "makeway/common/random.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace makeway {
namespace {

std::uint64_t splitmix64(std::uint64_t& state) {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

double to_unit(std::uint64_t bits) {
    return static_cast<double>(bits >> 11) * 0x1.0p-53;
}  // [0, 1)
double unit(Rng& rng) { return to_unit(rng()); }

}  // namespace

Rng make_rng(std::uint64_t seed, std::uint64_t stream) {
    std::uint64_t state = seed ^ (0xD1B54A32D192ED03ULL * (stream + 1));
    std::seed_seq seq{splitmix64(state), splitmix64(state), splitmix64(state), splitmix64(state)};
    return Rng(seq);
}

double uniform(Rng& rng, double lo, double hi) { return lo + (hi - lo) * unit(rng); }

double normal(Rng& rng, double mean, double stddev) {
    const double u1 = 1.0 - unit(rng);  // (0, 1]: log is finite
    const double u2 = unit(rng);
    return mean + stddev * std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

std::int64_t uniform_int(Rng& rng, std::int64_t lo, std::int64_t hi) {
    const auto span = static_cast<std::uint64_t>(hi - lo) + 1;
    if (span == 0) return static_cast<std::int64_t>(rng());  // full 64-bit range
    // Rejection sampling removes modulo bias.
    const std::uint64_t limit = std::numeric_limits<std::uint64_t>::max() -
                                std::numeric_limits<std::uint64_t>::max() % span;
    std::uint64_t x;
    do {
        x = rng();
    } while (x >= limit);
    return lo + static_cast<std::int64_t>(x % span);
}

bool bernoulli(Rng& rng, double p) { return unit(rng) < p; }

double counter_uniform(std::uint64_t seed, std::uint64_t counter) {
    std::uint64_t state = seed * 0x9E3779B97F4A7C15ULL + counter;
    splitmix64(state);
    return to_unit(splitmix64(state));
}

std::pair<double, double> counter_normal_pair(std::uint64_t seed, std::uint64_t counter) {
    std::uint64_t state = seed * 0x9E3779B97F4A7C15ULL + counter;
    splitmix64(state);
    while (true) {  // accepts with probability pi/4; the sequence is fixed by (seed, counter)
        const double u = 2.0 * to_unit(splitmix64(state)) - 1.0;
        const double v = 2.0 * to_unit(splitmix64(state)) - 1.0;
        const double s = u * u + v * v;
        if (s > 0.0 && s < 1.0) {
            const double f = std::sqrt(-2.0 * std::log(s) / s);
            return {u * f, v * f};
        }
    }
}

}  // namespace makeway

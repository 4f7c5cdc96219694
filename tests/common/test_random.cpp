#include <gtest/gtest.h>

#include <cmath>

#include "makeway/common/random.hpp"

namespace makeway {
namespace {

TEST(Random, SameSeedSameSequence) {
    Rng a = make_rng(42, 3), b = make_rng(42, 3);
    for (int i = 0; i < 100; ++i) {
        EXPECT_EQ(normal(a, 0, 1), normal(b, 0, 1));
        EXPECT_EQ(uniform(a, -1, 1), uniform(b, -1, 1));
    }
}

TEST(Random, StreamsAndSeedsDiffer) {
    Rng a = make_rng(42, 0), b = make_rng(42, 1), c = make_rng(43, 0);
    const auto x = a();
    EXPECT_NE(x, b());
    EXPECT_NE(x, c());
}

TEST(Random, DistributionMoments) {
    Rng rng = make_rng(1);
    constexpr int n = 200000;
    double sum = 0, sq = 0, usum = 0;
    std::int64_t lo = 10, hi = -10;
    for (int i = 0; i < n; ++i) {
        const double v = normal(rng, 2.0, 0.5);
        sum += v;
        sq += v * v;
        usum += uniform(rng, 0.0, 4.0);
        const auto k = uniform_int(rng, -3, 3);
        lo = std::min(lo, k);
        hi = std::max(hi, k);
    }
    const double mean = sum / n;
    EXPECT_NEAR(mean, 2.0, 0.01);
    EXPECT_NEAR(std::sqrt(sq / n - mean * mean), 0.5, 0.01);
    EXPECT_NEAR(usum / n, 2.0, 0.02);
    EXPECT_EQ(lo, -3);
    EXPECT_EQ(hi, 3);
}

}  // namespace
}  // namespace makeway

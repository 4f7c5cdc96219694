#pragma once
// Order statistics for benchmark reports (timings, errors): nearest rank, rounded; and the
// percentile bootstrap of a mean (Efron and Tibshirani 1993, ch. 13), for confidence intervals
// over benchmark scenes and for paired differences between methods on the same scenes.
#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

namespace makeway {

/// The q-quantile (q in [0, 1]) as the element at rank round(q (n - 1)) of the sorted values; 0
/// when empty.
inline double percentile(std::vector<double> v, double q) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1,
                      static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5))];
}

/// percentile(v, 0.5): the upper median for an even count.
inline double median(std::vector<double> v) { return percentile(std::move(v), 0.5); }

/// A mean with its percentile-bootstrap interval.
struct MeanInterval {
    double mean = 0.0, lo = 0.0, hi = 0.0;
    std::size_t n = 0;
};

/// The mean of `v` and its `level` percentile-bootstrap interval from `resamples` resamples with
/// replacement, drawn by a generator seeded with `seed`: the same values and seed give the same
/// interval on every machine (std::mt19937_64 is specified; indices come from its raw output).
/// Empty input: all zero.
inline MeanInterval bootstrap_mean(const std::vector<double>& v, std::uint64_t seed,
                                   int resamples = 2000, double level = 0.95) {
    MeanInterval out;
    out.n = v.size();
    if (v.empty()) return out;
    out.mean = std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
    std::mt19937_64 rng(seed);
    std::vector<double> means(static_cast<std::size_t>(std::max(resamples, 1)));
    for (double& m : means) {
        double sum = 0.0;
        for (std::size_t i = 0; i < v.size(); ++i) sum += v[rng() % v.size()];
        m = sum / static_cast<double>(v.size());
    }
    const double tail = 0.5 * (1.0 - level);
    out.lo = percentile(means, tail);
    out.hi = percentile(means, 1.0 - tail);
    return out;
}

}  // namespace makeway

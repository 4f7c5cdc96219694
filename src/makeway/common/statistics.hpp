#pragma once
// Order statistics for benchmark reports (timings, errors): nearest rank, rounded.
#include <algorithm>
#include <vector>

namespace makeway {

/// The q-quantile (q in [0, 1]) as the element at rank round(q (n - 1)) of the sorted values; 0 when empty.
inline double percentile(std::vector<double> v, double q) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5))];
}

/// percentile(v, 0.5): the upper median for an even count.
inline double median(std::vector<double> v) { return percentile(std::move(v), 0.5); }

}  // namespace makeway

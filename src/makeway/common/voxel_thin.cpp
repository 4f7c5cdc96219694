#include "makeway/common/voxel_thin.hpp"

#include <tsl/robin_set.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace makeway {
namespace {

// The packed key's low bits are one axis only: an identity hash (std::hash's) would put a wall's
// voxels in a few buckets of a power-of-two table. A multiply-xorshift spreads every axis.
struct MixHash {
    std::size_t operator()(std::uint64_t k) const {
        k ^= k >> 33;
        k *= 0xff51afd7ed558ccdULL;
        k ^= k >> 33;
        return static_cast<std::size_t>(k);
    }
};

}  // namespace

std::vector<Eigen::Vector3d> voxel_thin(const std::vector<Eigen::Vector3d>& points, double voxel) {
    // Voxel keys packed into 64 bits (21 bits per axis: +-1 million voxels) in an open-addressing
    // set: no allocation per voxel (a node-based set allocated and freed one per voxel, twice per
    // sweep in the odometry).
    auto key = [voxel](const Eigen::Vector3d& p) {
        std::uint64_t k = 0;
        for (int a = 0; a < 3; ++a) {
            // Clamped where the cast is defined: a finite point can lie up to 3e38 m away (a
            // damaged or hostile cloud); every such point then shares the edge voxel's key.
            const double q = std::clamp(p[a] / voxel, -0x1p62, 0x1p62);
            auto f = static_cast<std::int64_t>(q);  // std::floor without a libm call
            if (static_cast<double>(f) > q) --f;
            const auto v = f & ((std::int64_t{1} << 21) - 1);
            k = (k << 21) | static_cast<std::uint64_t>(v);
        }
        return k;
    };
    tsl::robin_set<std::uint64_t, MixHash> seen;
    seen.reserve(points.size() / 4 + 16);
    std::vector<Eigen::Vector3d> out;
    for (const auto& p : points) {
        if (p.allFinite() && seen.insert(key(p)).second) out.push_back(p);
    }
    return out;
}

}  // namespace makeway

#include "makeway/common/voxel_thin.hpp"

#include <tsl/robin_set.h>

#include <cstdint>

#include "makeway/common/floor_index.hpp"

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
            const auto v = floor_index(p[a], voxel) & ((std::int64_t{1} << 21) - 1);
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

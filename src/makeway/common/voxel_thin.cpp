#include "makeway/common/voxel_thin.hpp"

#include <cmath>
#include <cstdint>
#include <unordered_set>

namespace makeway {

std::vector<Eigen::Vector3d> voxel_thin(const std::vector<Eigen::Vector3d>& points, double voxel) {
    // Voxel keys packed into 64 bits (21 bits per axis: +-1 million voxels) in a hash set.
    auto key = [voxel](const Eigen::Vector3d& p) {
        std::uint64_t k = 0;
        for (int a = 0; a < 3; ++a) {
            const auto v =
                static_cast<std::int64_t>(std::floor(p[a] / voxel)) & ((std::int64_t{1} << 21) - 1);
            k = (k << 21) | static_cast<std::uint64_t>(v);
        }
        return k;
    };
    std::unordered_set<std::uint64_t> seen;
    seen.reserve(points.size());
    std::vector<Eigen::Vector3d> out;
    for (const auto& p : points) {
        if (p.allFinite() && seen.insert(key(p)).second) out.push_back(p);
    }
    return out;
}

}  // namespace makeway

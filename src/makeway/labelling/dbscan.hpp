#pragma once
// DBSCAN (Ester et al. 1996, as revisited by Schubert et al. 2017, the paper's clustering step):
// a point with at least `min_points` neighbours within `eps_m` (itself included) is a core point;
// clusters are the core points connected through eps-neighbourhoods plus the border points they
// reach. Neighbourhoods come from a k-d tree (nanoflann), so the cost is O(n log n) for the
// sparse, evenly spread points a LiDAR map gives.
#include <Eigen/Core>
#include <vector>

namespace makeway::labelling {

struct DbscanParams {
    double eps_m = 0.12;
    int min_points = 8;  ///< neighbours within eps (the point itself included) to be a core point
};

struct DbscanResult {
    static constexpr int kNoise = -1;
    std::vector<int> cluster;  ///< per point: its cluster (0 .. clusters-1) or kNoise
    int clusters = 0;
};

/// Clusters are numbered in the order of their first core point in the input; a border point
/// reachable from several clusters joins the first to reach it (the one ambiguity of DBSCAN).
DbscanResult dbscan(const std::vector<Eigen::Vector3d>& points, const DbscanParams& params);

/// The indices of each cluster's points, in input order.
std::vector<std::vector<std::size_t>> cluster_members(const DbscanResult& result);

}  // namespace makeway::labelling

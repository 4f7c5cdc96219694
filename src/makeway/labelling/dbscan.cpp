#include "makeway/labelling/dbscan.hpp"

#include <nanoflann.hpp>

namespace makeway::labelling {
namespace {

struct Adaptor {
    const std::vector<Eigen::Vector3d>* points;
    std::size_t kdtree_get_point_count() const { return points->size(); }
    double kdtree_get_pt(std::size_t i, std::size_t dim) const {
        return (*points)[i][static_cast<Eigen::Index>(dim)];
    }
    template <class Bbox>
    bool kdtree_get_bbox(Bbox&) const {
        return false;
    }
};
using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Adaptor>,
                                                 Adaptor, 3, std::size_t>;

}  // namespace

DbscanResult dbscan(const std::vector<Eigen::Vector3d>& points, const DbscanParams& params) {
    DbscanResult result;
    result.cluster.assign(points.size(), DbscanResult::kNoise);
    if (points.empty()) return result;
    const Adaptor adaptor{&points};
    Tree tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(10));
    tree.buildIndex();
    const double radius2 =
        params.eps_m * params.eps_m;  // nanoflann's L2 adaptors take squared radii
    std::vector<std::pair<std::size_t, double>> found;
    auto neighbours = [&](std::size_t i) {
        found.clear();
        tree.radiusSearch(points[i].data(), radius2, found,
                          nanoflann::SearchParams(32, 0.0f, false));
        std::vector<std::size_t> out;
        out.reserve(found.size());
        for (const auto& [j, d2] : found) {
            if (d2 <= radius2) out.push_back(j);
        }
        return out;
    };
    const auto min_points = static_cast<std::size_t>(std::max(1, params.min_points));
    std::vector<char> visited(points.size(), 0);
    std::vector<std::size_t> frontier;
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (visited[i]) continue;
        visited[i] = 1;
        std::vector<std::size_t> seeds = neighbours(i);
        if (seeds.size() < min_points) continue;  // noise unless a later core point reaches it
        const int id = result.clusters++;
        result.cluster[i] = id;
        frontier = std::move(seeds);
        while (!frontier.empty()) {
            const std::size_t j = frontier.back();
            frontier.pop_back();
            if (result.cluster[j] == DbscanResult::kNoise)
                result.cluster[j] = id;  // border or core
            if (visited[j]) continue;
            visited[j] = 1;
            std::vector<std::size_t> more = neighbours(j);
            if (more.size() < min_points) continue;  // a border point: reached, not expanded
            for (std::size_t k : more) {
                if (!visited[k] || result.cluster[k] == DbscanResult::kNoise) frontier.push_back(k);
            }
        }
    }
    return result;
}

std::vector<std::vector<std::size_t>> cluster_members(const DbscanResult& result) {
    std::vector<std::vector<std::size_t>> members(static_cast<std::size_t>(result.clusters));
    for (std::size_t i = 0; i < result.cluster.size(); ++i) {
        if (result.cluster[i] >= 0)
            members[static_cast<std::size_t>(result.cluster[i])].push_back(i);
    }
    return members;
}

}  // namespace makeway::labelling

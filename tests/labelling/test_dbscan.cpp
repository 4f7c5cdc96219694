// DBSCAN against the textbook algorithm with brute-force neighbourhoods, on random sets.
#include <gtest/gtest.h>

#include <random>

#include "makeway/labelling/dbscan.hpp"

namespace makeway::labelling {
namespace {

// Ester et al.'s algorithm, visiting points in input order, neighbours by an O(n^2) scan.
DbscanResult brute_force(const std::vector<Eigen::Vector3d>& pts, const DbscanParams& p) {
    DbscanResult r;
    r.cluster.assign(pts.size(), DbscanResult::kNoise);
    auto neighbours = [&](std::size_t i) {
        std::vector<std::size_t> out;
        for (std::size_t j = 0; j < pts.size(); ++j) {
            if ((pts[i] - pts[j]).squaredNorm() <= p.eps_m * p.eps_m) out.push_back(j);
        }
        return out;
    };
    std::vector<char> visited(pts.size(), 0);
    for (std::size_t i = 0; i < pts.size(); ++i) {
        if (visited[i]) continue;
        visited[i] = 1;
        std::vector<std::size_t> seeds = neighbours(i);
        if (seeds.size() < static_cast<std::size_t>(p.min_points)) continue;
        const int id = r.clusters++;
        r.cluster[i] = id;
        std::vector<std::size_t> stack = seeds;
        while (!stack.empty()) {
            const std::size_t j = stack.back();
            stack.pop_back();
            if (r.cluster[j] == DbscanResult::kNoise) r.cluster[j] = id;
            if (visited[j]) continue;
            visited[j] = 1;
            const std::vector<std::size_t> more = neighbours(j);
            if (more.size() < static_cast<std::size_t>(p.min_points)) continue;
            for (std::size_t k : more) {
                if (!visited[k] || r.cluster[k] == DbscanResult::kNoise) stack.push_back(k);
            }
        }
    }
    return r;
}

bool is_core(const std::vector<Eigen::Vector3d>& pts, std::size_t i, const DbscanParams& p) {
    int n = 0;
    for (const Eigen::Vector3d& q : pts) n += (pts[i] - q).squaredNorm() <= p.eps_m * p.eps_m;
    return n >= p.min_points;
}

TEST(Dbscan, MatchesTheBruteForceReferenceOnRandomSets) {
    for (std::uint32_t seed = 0; seed < 8; ++seed) {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        std::normal_distribution<double> g(0.0, 0.08);
        std::vector<Eigen::Vector3d> pts;
        // A few blobs and uniform noise: cores, borders and noise all occur.
        for (int b = 0; b < 5; ++b) {
            const Eigen::Vector3d c(3 * u(rng), 3 * u(rng), u(rng));
            for (int k = 0; k < 60; ++k) pts.push_back(c + Eigen::Vector3d(g(rng), g(rng), g(rng)));
        }
        for (int k = 0; k < 100; ++k)
            pts.push_back(Eigen::Vector3d(3 * u(rng), 3 * u(rng), u(rng)));
        const DbscanParams p{0.1 + 0.02 * seed, 4 + static_cast<int>(seed % 3)};
        const DbscanResult got = dbscan(pts, p);
        const DbscanResult want = brute_force(pts, p);
        ASSERT_EQ(got.clusters, want.clusters) << "seed " << seed;
        // Same traversal order: core and noise points agree exactly; a border point reachable from
        // two clusters may join either (DBSCAN's one ambiguity), but always one it touches.
        for (std::size_t i = 0; i < pts.size(); ++i) {
            if (is_core(pts, i, p) || want.cluster[i] == DbscanResult::kNoise) {
                EXPECT_EQ(got.cluster[i], want.cluster[i]) << "seed " << seed << " point " << i;
            } else {
                ASSERT_NE(got.cluster[i], DbscanResult::kNoise);
                bool touches = false;
                for (std::size_t j = 0; j < pts.size(); ++j) {
                    touches |= got.cluster[j] == got.cluster[i] && is_core(pts, j, p) &&
                               (pts[i] - pts[j]).norm() <= p.eps_m;
                }
                EXPECT_TRUE(touches) << "seed " << seed << " point " << i;
            }
        }
        EXPECT_GT(got.clusters, 0);
    }
}

TEST(Dbscan, DegenerateInput) {
    EXPECT_EQ(dbscan({}, {}).clusters, 0);
    // One point is a cluster of one when min_points is 1, noise otherwise.
    EXPECT_EQ(dbscan({Eigen::Vector3d::Zero()}, {0.1, 1}).clusters, 1);
    EXPECT_EQ(dbscan({Eigen::Vector3d::Zero()}, {0.1, 2}).cluster[0], DbscanResult::kNoise);
    // Identical points are each other's neighbours.
    const DbscanResult same =
        dbscan(std::vector<Eigen::Vector3d>(10, Eigen::Vector3d(1, 2, 3)), {0.01, 10});
    EXPECT_EQ(same.clusters, 1);
    // Two lines 0.5 m apart stay two clusters at eps 0.2, members listed per cluster.
    std::vector<Eigen::Vector3d> lines;
    for (int k = 0; k < 20; ++k) lines.push_back(Eigen::Vector3d(0.1 * k, 0, 0));
    for (int k = 0; k < 20; ++k) lines.push_back(Eigen::Vector3d(0.1 * k, 0.5, 0));
    const auto members = cluster_members(dbscan(lines, {0.2, 3}));
    ASSERT_EQ(members.size(), 2u);
    EXPECT_EQ(members[0].size(), 20u);
    EXPECT_EQ(members[1].front(), 20u);
}

}  // namespace
}  // namespace makeway::labelling

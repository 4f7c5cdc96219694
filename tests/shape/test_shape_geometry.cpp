// The shape networks' geometry: the 7-DoF solve (exact, weighted, robust, degenerate), signed
// distances against brute force and an analytic box, isosurfaces of an analytic sphere, TSDF
// fusion of a wall, and the completion metrics.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "makeway/common/random.hpp"
#include "makeway/shape/mesh_sdf.hpp"
#include "makeway/shape/similarity.hpp"
#include "makeway/shape/volume.hpp"
#include "makeway/sim/furniture.hpp"
#include "makeway/sim/mesh_primitives.hpp"

namespace makeway::shape {
namespace {

Similarity3 known(bool upright) {
    Similarity3 T;
    T.scale = 0.73;
    T.rotation =
        upright
            ? Eigen::AngleAxisd(2.1, Eigen::Vector3d::UnitZ()).toRotationMatrix()
            : Eigen::Matrix3d(Eigen::AngleAxisd(0.9, Eigen::Vector3d(0.3, -0.5, 0.8).normalized()));
    T.translation = Eigen::Vector3d(1.5, -2.25, 0.4);
    return T;
}

void random_pairs(const Similarity3& T, int n, std::uint64_t seed, std::vector<Eigen::Vector3d>& v,
                  std::vector<Eigen::Vector3d>& p) {
    Rng rng = make_rng(seed);
    for (int i = 0; i < n; ++i) {
        v.emplace_back(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
        p.push_back(T.apply(v.back()));
    }
}

void expect_same(const Similarity3& a, const Similarity3& b, double tol) {
    EXPECT_NEAR(a.scale, b.scale, tol);
    EXPECT_LT((a.rotation - b.rotation).norm(), tol);
    EXPECT_LT((a.translation - b.translation).norm(), tol);
}

TEST(Similarity, RecoversAKnownSimilarityExactly) {
    for (const bool upright : {false, true}) {
        const Similarity3 T = known(upright);
        std::vector<Eigen::Vector3d> v, p;
        random_pairs(T, 50, 1, v, p);
        std::vector<double> w(v.size());
        Rng rng = make_rng(2);
        for (double& x : w) x = uniform(rng, 0.1, 2.0);  // any positive weights: still exact
        const auto got = solve_similarity(v, p, w, upright);
        ASSERT_TRUE(got.has_value());
        expect_same(*got, T, 1e-9);
        EXPECT_NEAR(got->yaw_rad(), upright ? 2.1 : got->yaw_rad(), 1e-9);
    }
}

TEST(Similarity, ZeroWeightsIgnoreOutliersExactly) {
    const Similarity3 T = known(false);
    std::vector<Eigen::Vector3d> v, p;
    random_pairs(T, 30, 3, v, p);
    std::vector<double> w(v.size(), 1.0);
    for (std::size_t i = 0; i < v.size(); i += 3) p[i] += Eigen::Vector3d(5, -3, 1), w[i] = 0.0;
    const auto got = solve_similarity(v, p, w, false);
    ASSERT_TRUE(got.has_value());
    expect_same(*got, T, 1e-9);
    std::fill(w.begin(), w.end(), 1.0);  // weighted equally they pull it off
    EXPECT_GT((solve_similarity(v, p, w, false)->translation - T.translation).norm(), 0.1);
}

TEST(Similarity, DegenerateInputHasNoAnswer) {
    const std::vector<Eigen::Vector3d> two{{0, 0, 0}, {1, 0, 0}};
    EXPECT_FALSE(solve_similarity(two, two, {1, 1}, false));  // 2 pairs, full
    EXPECT_TRUE(solve_similarity(two, two, {1, 1}, true));    // 2 pairs upright: enough
    const std::vector<Eigen::Vector3d> line{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}};
    EXPECT_FALSE(solve_similarity(line, line, {1, 1, 1, 1}, false));  // collinear
    const std::vector<Eigen::Vector3d> same(4, Eigen::Vector3d(1, 2, 3));
    EXPECT_FALSE(solve_similarity(same, same, {1, 1, 1, 1}, true));  // one point
    const std::vector<Eigen::Vector3d> vertical{{0, 0, 0}, {0, 0, 1}, {0, 0, 2}};
    EXPECT_FALSE(solve_similarity(vertical, vertical, {1, 1, 1}, true));  // no yaw to see
    EXPECT_FALSE(solve_similarity(two, two, {1, -1}, true));              // negative weight
    EXPECT_FALSE(solve_similarity(two, two, {1, NAN}, true));
    EXPECT_FALSE(solve_similarity(two, two, {1}, true));  // sizes differ
    EXPECT_FALSE(solve_similarity_robust({}, {}, {}));
}

TEST(Similarity, RobustSolveRecoversThePoseWithHalfTheCorrespondencesWrong) {
    for (const bool upright : {true, false}) {
        const Similarity3 T = known(upright);
        std::vector<Eigen::Vector3d> v, p;
        random_pairs(T, 200, 4, v, p);
        Rng rng = make_rng(5);
        for (std::size_t i = 0; i < v.size(); i += 2) {  // 50 %: canonical guesses anywhere
            v[i] = Eigen::Vector3d(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
        }
        RobustSolveParams params;
        params.upright = upright;
        params.hypotheses = upright ? 200 : 400;
        const auto got = solve_similarity_robust(v, p, std::vector<double>(v.size(), 1.0), params);
        ASSERT_TRUE(got.has_value());
        expect_same(got->similarity, T, 1e-9);
        EXPECT_EQ(got->inliers, 100u);
        // The plain least squares on the same pairs is far off: the outliers matter.
        const auto plain = solve_similarity(v, p, std::vector<double>(v.size(), 1.0), upright);
        EXPECT_GT(std::abs(plain->scale - T.scale), 0.1);
    }
}

double brute_force_distance(const MeshSdf& sdf, const Eigen::Vector3d& q) {
    double best = INFINITY;
    for (const auto& t : sdf.triangles()) {
        const auto& v = sdf.vertices();
        best = std::min(best, (closest_point_on_triangle(q, v[t[0]], v[t[1]], v[t[2]]) - q).norm());
    }
    return best;
}

TEST(MeshSdf, DistanceOfAProceduralChairMatchesBruteForce) {
    const sim::FurnitureModel chair = sim::make_furniture(sim::FurnitureStyle::kOfficeChair, 7);
    const MeshSdf sdf(chair.mesh_object, chair.box_object.centre_m,
                      2.0 / chair.box_object.size_m.norm());
    Rng rng = make_rng(8);
    const auto surface = sdf.sample_surface(300, 9);
    for (int i = 0; i < 1200; ++i) {
        // Uniform in the cube, and near the surface where the search is hardest.
        Eigen::Vector3d q(uniform(rng, -1.2, 1.2), uniform(rng, -1.2, 1.2),
                          uniform(rng, -1.2, 1.2));
        if (i % 2)
            q = surface[static_cast<std::size_t>(i % 300)] +
                Eigen::Vector3d(normal(rng, 0, 0.03), normal(rng, 0, 0.03), normal(rng, 0, 0.03));
        ASSERT_NEAR(sdf.unsigned_distance(q), brute_force_distance(sdf, q), 1e-12) << q.transpose();
    }
    for (const auto& s : surface) EXPECT_LT(sdf.unsigned_distance(s), 1e-9);
}

TEST(MeshSdf, SignedDistanceOfOverlappingBoxesIsTheUnionsAnalyticValue) {
    // Two closed boxes that overlap: the union's inside is where either box is.
    TriangleMesh mesh;
    sim::add_box(mesh, {0, 0, 0}, {2, 1, 1});
    sim::add_box(mesh, {0.8, 0, 0}, {1, 1, 3});
    const MeshSdf sdf(mesh);
    auto box_sdf = [](const Eigen::Vector3d& q, const Eigen::Vector3d& c,
                      const Eigen::Vector3d& half) {
        const Eigen::Vector3d d = (q - c).cwiseAbs() - half;
        return d.cwiseMax(0.0).norm() + std::min(d.maxCoeff(), 0.0);
    };
    Rng rng = make_rng(10);
    for (int i = 0; i < 2000; ++i) {
        const Eigen::Vector3d q(uniform(rng, -2, 2), uniform(rng, -1.5, 1.5),
                                uniform(rng, -2.5, 2.5));
        const double a = box_sdf(q, {0, 0, 0}, {1, 0.5, 0.5}),
                     b = box_sdf(q, {0.8, 0, 0}, {0.5, 0.5, 1.5});
        const bool inside = std::min(a, b) < 0;
        if (std::abs(std::min(a, b)) < 1e-6) continue;  // on a face
        ASSERT_EQ(sdf.inside(q), inside) << q.transpose();
        const double w = sdf.winding_number(q);
        EXPECT_NEAR(w, inside ? (a < 0) + (b < 0) : 0.0, 1e-6);
        if (!inside) {
            ASSERT_NEAR(sdf.signed_distance(q), std::min(a, b),
                        1e-6);  // outside a union: the nearer part (float vertices)
        }
    }
}

TEST(Isosurface, SphereIsClosedOutwardAndOfTheRightVolume) {
    const double r = 0.7, h = 2.0 / 40;
    const Eigen::Vector3i dims(41, 41, 41);
    const Eigen::Vector3d origin(-1, -1, -1);
    std::vector<float> values;
    for (int z = 0; z < 41; ++z)
        for (int y = 0; y < 41; ++y)
            for (int x = 0; x < 41; ++x)
                values.push_back(
                    static_cast<float>((origin + h * Eigen::Vector3d(x, y, z)).norm() - r));
    const TriangleMesh mesh = extract_isosurface(values, dims, origin, h, 0.0, true);
    ASSERT_GT(mesh.triangles.size(), 1000u);
    EXPECT_EQ(mesh.validity_error(), "");
    for (const auto& v : mesh.vertices_m) EXPECT_NEAR(v.cast<double>().norm(), r, 0.01);
    // Closed and manifold: every edge in exactly two triangles, once each way.
    std::map<std::pair<int, int>, int> directed;
    double volume = 0.0;
    for (const auto& t : mesh.triangles) {
        for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
        const Eigen::Vector3d a = mesh.vertices_m[static_cast<std::size_t>(t[0])].cast<double>(),
                              b = mesh.vertices_m[static_cast<std::size_t>(t[1])].cast<double>(),
                              c = mesh.vertices_m[static_cast<std::size_t>(t[2])].cast<double>();
        EXPECT_GT((b - a).cross(c - a).dot(a + b + c), 0.0);  // faces outward
        volume += a.dot(b.cross(c)) / 6.0;
    }
    for (const auto& [edge, count] : directed) {
        ASSERT_EQ(count, 1);
        ASSERT_EQ(directed.count({edge.second, edge.first}), 1u);
    }
    EXPECT_EQ(static_cast<long>(mesh.vertices_m.size()) - static_cast<long>(directed.size() / 2) +
                  static_cast<long>(mesh.triangles.size()),
              2);  // Euler: a sphere
    EXPECT_NEAR(volume, 4.0 / 3.0 * M_PI * r * r * r, 0.02 * 4.0 / 3.0 * M_PI * r * r * r);
    // An occupancy field (inside above the level) gives the same surface, facing the same way.
    std::vector<float> occ(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) occ[i] = -values[i];
    const TriangleMesh same = extract_isosurface(occ, dims, origin, h, 0.0, false);
    EXPECT_EQ(same.triangles.size(), mesh.triangles.size());
    EXPECT_TRUE(extract_isosurface(values, {1, 41, 41}, origin, h, 0.0, true).triangles.empty());
}

TEST(Tsdf, AWallSeenHeadOnIsFreeInFrontNegativeBehindAndUnseenBeyond) {
    CubeGrid grid;
    grid.resolution = 20;
    grid.half_extent = 1.0;  // cells of 0.1
    TsdfVolume tsdf(grid, 2.0);
    std::vector<Eigen::Vector3d> wall;
    for (double y = -0.95; y <= 0.95; y += 0.02)
        for (double z = -0.95; z <= 0.95; z += 0.02) wall.emplace_back(0.0, y, z);
    tsdf.integrate(wall, Eigen::Vector3d(-5, 0, 0));
    auto at = [&](double x) {  // the cell centred at (x, 0.05, 0.05)
        const int i = static_cast<int>(std::floor((x + 1.0) / 0.1));
        const std::size_t k = grid.index(i, 10, 10);
        return std::make_pair(tsdf.tsdf()[k], tsdf.weight()[k]);
    };
    EXPECT_FLOAT_EQ(at(-0.55).first, 1.0f);  // free: far in front of the wall
    EXPECT_GT(at(-0.55).second, 0.0f);
    EXPECT_NEAR(at(-0.05).first, 0.25, 0.08);  // 5 cm in front with a 20 cm truncation
    EXPECT_NEAR(at(0.15).first, -0.75, 0.08);  // 15 cm behind
    EXPECT_EQ(at(0.45).second, 0.0f);          // beyond the truncation: never seen
    EXPECT_GT(tsdf.observed_cells(), 0u);
}

TEST(Metrics, ChamferAndIouKnownAnswers) {
    const std::vector<Eigen::Vector3d> a{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    std::vector<Eigen::Vector3d> b = a;
    EXPECT_DOUBLE_EQ(chamfer_l1(a, b), 0.0);
    for (auto& p : b) p.z() += 0.05;
    EXPECT_NEAR(chamfer_l1(a, b), 0.05, 1e-12);
    EXPECT_TRUE(std::isinf(chamfer_l1(a, {})));
    EXPECT_DOUBLE_EQ(volumetric_iou({1, 1, 0, 0}, {1, 0, 1, 0}), 1.0 / 3.0);
    EXPECT_DOUBLE_EQ(volumetric_iou({0, 0}, {0, 0}), 1.0);
}

}  // namespace
}  // namespace makeway::shape

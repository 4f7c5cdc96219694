#include "makeway/eval/shape_bench.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include "makeway/common/angles.hpp"
#include "makeway/common/statistics.hpp"
#include "makeway/common/stopwatch.hpp"
#include "makeway/eval/verify_bench.hpp"
#include "makeway/shape/mesh_sdf.hpp"

namespace makeway::eval {

namespace {

double median_of(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

double quantile_of(std::vector<double> v, double q) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())))];
}

// Chamfer-L1 [m] of a predicted surface (mesh, or points) to the true surface samples.
double chamfer_m(const TriangleMesh& mesh, const std::vector<Eigen::Vector3d>& truth,
                 double scale_m) {
    if (mesh.triangles.empty()) return 1.0 * scale_m;  // nothing predicted: one canonical unit
    const shape::MeshSdf sdf(mesh);
    return shape::chamfer_l1(sdf.sample_surface(truth.size(), 5), truth) * scale_m;
}

struct SetAccumulator {
    std::vector<double> yaw_err, centre_err;
    std::size_t views = 0, failed = 0, yaw_scored = 0, yaw_ok = 0, centre_ok = 0;
    std::vector<double> cp, c0, c1, ip, i0, i1;
};

}  // namespace

ShapeBenchResult run_shape_bench(
    const shape::ShapeModel& model, const ShapeBenchParams& p,
    const std::function<void(const std::string&, int, int)>& progress) {
    ShapeBenchResult result;
    std::vector<double> fn_ms, f1_update_ms, f1_mesh_ms, f0_ms;
    struct SetSpec {
        std::string name;
        std::vector<std::string> only;
    };
    std::vector<SetSpec> specs{{"held-out seeds", {}}};
    if (!p.left_out_styles.empty()) specs.push_back({"left-out styles", p.left_out_styles});
    const shape::CubeGrid& grid = model.params().grid;
    const std::vector<Eigen::Vector3d> centres = grid.centres();
    int showcase_left[2] = {p.showcase, p.showcase};
    for (std::size_t si = 0; si < specs.size(); ++si) {
        ShapeDatasetParams dp;
        dp.scenes = p.scenes;
        dp.seed = p.seed + 17 * si;
        dp.only_styles = specs[si].only;
        dp.sdf_samples = 0;
        dp.occupancy_samples = 0;
        const ShapeDataset data = generate_shape_dataset(dp, [&](int done, int total) {
            if (progress) progress("rendering " + specs[si].name, done, total);
        });
        SetAccumulator acc[2];
        // Pose per view.
        for (std::size_t v = 0; v < data.views.size(); ++v) {
            const shape::ShapeView& view = data.views[v];
            if (data.own_points_of_view[v] < p.min_points) continue;
            const shape::ShapeExample& ex = data.shapes[static_cast<std::size_t>(view.shape)];
            const int c = shape::shape_class_index(ex.cls);
            if (c < 0) continue;
            SetAccumulator& a = acc[c];
            ++a.views;
            const auto t0 = SteadyClock::now();
            const auto T = model.estimate_pose(ex.cls, view.points, p.solve);
            fn_ms.push_back(ms_since(t0));
            const auto yaw_err =
                yaw_error_deg(ex.style, T ? T->yaw_rad() : 0.0, view.truth.yaw_rad());
            if (!T) {
                ++a.failed;
                if (yaw_err) ++a.yaw_scored, a.yaw_err.push_back(180.0);
                a.centre_err.push_back(1e9);
                continue;
            }
            if (yaw_err) {
                ++a.yaw_scored;
                a.yaw_ok += *yaw_err <= 10.0;
                a.yaw_err.push_back(*yaw_err);
            }
            const double centre = (T->translation - view.truth.translation).head<2>().norm();
            a.centre_ok += centre <= 0.05;
            a.centre_err.push_back(centre);
        }
        // Completion per object, every view of it fused, in its true canonical frame.
        std::map<std::pair<int, std::uint32_t>, std::vector<std::size_t>> views_of;
        for (std::size_t v = 0; v < data.views.size(); ++v)
            views_of[{data.scene_of_view[v], data.object_of_view[v]}].push_back(v);
        int done = 0;
        for (const auto& [key, vs] : views_of) {
            if (!p.completion) break;
            if (progress)
                progress("completing " + specs[si].name, ++done, static_cast<int>(views_of.size()));
            std::size_t own = 0;
            for (const std::size_t v : vs) own += data.own_points_of_view[v];
            if (own < p.min_points) continue;
            const int shape_index = data.views[vs.front()].shape;
            const shape::ShapeExample& ex = data.shapes[static_cast<std::size_t>(shape_index)];
            const int c = shape::shape_class_index(ex.cls);
            if (c < 0) continue;
            const double scale = data.scale_m[static_cast<std::size_t>(shape_index)];
            std::vector<std::vector<Eigen::Vector3d>> views;
            std::vector<Eigen::Vector3d> origins, partial;
            for (const std::size_t v : vs) {
                const shape::ShapeView& view = data.views[v];
                views.emplace_back();
                for (const auto& q : view.points)
                    views.back().push_back(view.truth.inverse_apply(q));
                origins.push_back(view.truth.inverse_apply(view.origin));
                partial.insert(partial.end(), views.back().begin(), views.back().end());
            }
            // Timing of one update: a view fused, the encoder run (its features are what a later
            // query reads), and separately the whole-grid query and isosurface.
            {
                const auto t0 = SteadyClock::now();
                shape::TsdfVolume one(grid, model.params().truncation_cells);
                one.integrate(views.front(), origins.front());
                (void)model.occupancy(ex.cls, one, shape::Latent{}, {Eigen::Vector3d::Zero()});
                f1_update_ms.push_back(ms_since(t0));
            }
            shape::CompletionParams cp;
            cp.fit_iterations = p.fit_iterations;
            auto t0 = SteadyClock::now();
            const shape::Completion done_shape =
                shape::complete_shape(model, ex.cls, views, origins, cp);
            const double total_ms = ms_since(t0);
            // F_1 on the grid + isosurface timed apart; F_0's share (the code fit and its field) is
            // the rest of the completion's time.
            t0 = SteadyClock::now();
            const shape::TsdfVolume fused = shape::fuse_views(model, views, origins);
            const auto occ = model.occupancy(ex.cls, fused, done_shape.code, centres);
            const TriangleMesh mesh = shape::grid_isosurface(grid, occ, 0.5, false);
            f1_mesh_ms.push_back(ms_since(t0));
            f0_ms.push_back(total_ms - f1_mesh_ms.back());
            // Scores.
            const shape::MeshSdf truth_sdf(
                data.mesh_object[static_cast<std::size_t>(shape_index)],
                data.box_object[static_cast<std::size_t>(shape_index)].centre_m, 1.0 / scale);
            const std::vector<Eigen::Vector3d>& truth_surface =
                data.surface[static_cast<std::size_t>(shape_index)];
            std::vector<std::uint8_t> truth_occ(centres.size()), part_occ(centres.size(), 0),
                prior_occ(centres.size()), done_occ(centres.size());
            for (std::size_t i = 0; i < centres.size(); ++i) {
                truth_occ[i] = truth_sdf.inside(centres[i]);
                prior_occ[i] = done_shape.prior_sdf[i] < 0.0f;
                done_occ[i] = done_shape.occupancy[i] > 0.5f;
            }
            for (const auto& q : partial) {
                if (!(q.array().abs() < grid.half_extent).all())
                    continue;  // off the grid (also NaN)
                const Eigen::Array3i cell =
                    ((q.array() + grid.half_extent) / grid.cell()).floor().cast<int>();
                if ((cell >= 0).all() && (cell < grid.resolution).all())
                    part_occ[grid.index(cell.x(), cell.y(), cell.z())] = 1;
            }
            SetAccumulator& a = acc[c];
            a.cp.push_back(shape::chamfer_l1(partial, truth_surface) * scale);
            a.c0.push_back(chamfer_m(done_shape.prior_mesh, truth_surface, scale));
            a.c1.push_back(chamfer_m(done_shape.mesh, truth_surface, scale));
            a.ip.push_back(shape::volumetric_iou(part_occ, truth_occ));
            a.i0.push_back(shape::volumetric_iou(prior_occ, truth_occ));
            a.i1.push_back(shape::volumetric_iou(done_occ, truth_occ));
            if (si == 0 && showcase_left[c] > 0 && own >= 3 * p.min_points) {
                --showcase_left[c];
                ShowcaseShape s;
                s.name = std::string(to_string(ex.cls)) + ", " + ex.style;
                s.partial = partial;
                s.prior = done_shape.prior_mesh;
                s.completed = done_shape.mesh;
                for (const auto& q :
                     data.mesh_object[static_cast<std::size_t>(shape_index)].vertices_m) {
                    s.truth.vertices_m.push_back(
                        ((q.cast<double>() -
                          data.box_object[static_cast<std::size_t>(shape_index)].centre_m) /
                         scale)
                            .cast<float>());
                }
                s.truth.triangles =
                    data.mesh_object[static_cast<std::size_t>(shape_index)].triangles;
                result.showcase.push_back(std::move(s));
            }
        }
        ShapeBenchSet set;
        set.name = specs[si].name;
        for (int c = 0; c < 2; ++c) {
            const SetAccumulator& a = acc[c];
            PoseStats& ps = set.pose[c];
            ps.views = a.views;
            ps.failed = a.failed;
            ps.yaw_scored = a.yaw_scored;
            ps.yaw_within_10deg =
                a.yaw_scored ? static_cast<double>(a.yaw_ok) / static_cast<double>(a.yaw_scored)
                             : 0.0;
            ps.centre_within_5cm =
                a.views ? static_cast<double>(a.centre_ok) / static_cast<double>(a.views) : 0.0;
            ps.median_yaw_error_deg = median_of(a.yaw_err);
            ps.median_centre_error_m = median_of(a.centre_err);
            CompletionStats& cs = set.completion[c];
            cs.objects = a.cp.size();
            auto mean = [](const std::vector<double>& v) {
                return v.empty() ? 0.0
                                 : std::accumulate(v.begin(), v.end(), 0.0) /
                                       static_cast<double>(v.size());
            };
            cs.chamfer_partial_m = mean(a.cp);
            cs.chamfer_prior_m = mean(a.c0);
            cs.chamfer_completed_m = mean(a.c1);
            cs.iou_partial = mean(a.ip);
            cs.iou_prior = mean(a.i0);
            cs.iou_completed = mean(a.i1);
        }
        result.sets.push_back(set);
    }
    result.fn_ms_median = median_of(fn_ms);
    result.fn_ms_p90 = quantile_of(fn_ms, 0.9);
    result.f1_update_ms_median = median_of(f1_update_ms);
    result.f1_mesh_ms_median = median_of(f1_mesh_ms);
    result.f0_fit_ms_median = median_of(f0_ms);
    return result;
}

}  // namespace makeway::eval

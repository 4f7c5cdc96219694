#include "makeway/pipeline/tracked_shapes.hpp"

#include <stdexcept>

#include "makeway/pipeline/param_tables.hpp"
#include "makeway/pipeline/system_params.hpp"

namespace makeway::pipeline {

std::vector<std::string> TrackedShapeParams::validate() const {
    std::vector<std::string> problems = tracked_shape_table().problems(*this);
    if (!(ground_band_m >= 0.0 && ground_band_m <= 10.0))
        problems.push_back("ground_band_m must be in [0, 10]");
    return problems;
}

TrackedShapes::TrackedShapes(const verification::ShapePrior* prior,
                             const TrackedShapeParams& params)
    : prior_(prior), params_(params) {
    if (!prior_) throw std::invalid_argument("TrackedShapes needs a shape prior");
    throw_if_problems(params_.validate());
}

std::optional<verification::ShapePrior::Estimate> TrackedShapes::estimate(
    const std::vector<Eigen::Vector3d>& segment, ObjectClass cls, double floor_z_m) const {
    // Where the segment stands: the centroid of its returns above the floor band, in the world.
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    std::size_t n = 0;
    for (const auto& p : segment) {
        if (p.z() > floor_z_m + params_.ground_band_m) centroid += p, ++n;
    }
    if (n > 0) {
        const Eigen::Vector3d c_world = T_world_sensor_ * (centroid / static_cast<double>(n));
        const Shape* best = nullptr;
        double best_d = params_.match_distance_m;
        for (const auto& [id, s] : shapes_) {
            if (s.cls != cls) continue;
            const double d = ((s.T_world_object * s.centre_object) - c_world).head<2>().norm();
            if (d <= best_d) best_d = d, best = &s;
        }
        if (best) {
            Estimate e;
            e.mesh_object = best->mesh_object;
            e.T_sensor_object = T_world_sensor_.inverse() * best->T_world_object;
            e.scale = best->scale;
            e.offset_m = best->offset_m;
            return e;
        }
    }
    return prior_->estimate(segment, cls, floor_z_m);
}

namespace {

// The mesh's box centre: where estimate() looks for the object.
Eigen::Vector3d box_centre(const TriangleMesh& mesh) {
    Eigen::Vector3d lo, hi;
    mesh_bounds(mesh, lo, hi);
    return 0.5 * (lo + hi);
}

}  // namespace

std::size_t TrackedShapes::add_views(const PointCloud& cloud,
                                     const std::vector<verification::VerifiedDetection>& verified,
                                     const std::vector<int>& track_of_accepted,
                                     const std::unordered_set<std::uint32_t>& live) {
    for (auto it = shapes_.begin(); it != shapes_.end();)
        it = live.count(it->first) ? std::next(it) : shapes_.erase(it);
    std::size_t completed = 0, accepted = 0;
    for (const verification::VerifiedDetection& v : verified) {
        if (!v.accepted) continue;
        const std::size_t k = accepted++;
        if (!v.shape || k >= track_of_accepted.size() || track_of_accepted[k] < 0) continue;
        const auto id = static_cast<std::uint32_t>(track_of_accepted[k]);
        if (!live.count(id)) continue;
        auto [it, is_new] = shapes_.try_emplace(id);
        Shape& s = it->second;
        if (is_new || s.cls != v.detection.cls) {
            // The first fit (or the tracker's class changed its mind): this estimate's frame and
            // mesh.
            s = Shape{};
            s.cls = v.detection.cls;
            s.mesh_object = v.shape->mesh_object;
            s.centre_object = box_centre(s.mesh_object);
            s.scale = v.shape->scale;
            s.offset_m = v.shape->offset_m;
        }
        // The view: the keyframe's returns in the fitted box (grown), in the object frame the fit
        // found.
        const Isometry3 T_object_sensor = v.T_sensor_object.inverse();
        View view;
        view.origin_object = T_object_sensor.translation();
        for (const auto& p :
             verification::segment_points(cloud, v.box_sensor, params_.view_margin_m)) {
            const Eigen::Vector3d q = T_object_sensor * p;
            if (q.z() > params_.ground_band_m) view.points_object.push_back(q);
        }
        s.T_world_object = T_world_sensor_ * v.T_sensor_object;
        if (view.points_object.empty()) continue;
        s.views.push_back(std::move(view));
        while (s.views.size() > params_.max_views) s.views.pop_front();
        // One view: the prior's mesh was completed from it already.
        if (s.views.size() < 2) continue;
        if (auto mesh =
                prior_->complete({s.views.begin(), s.views.end()}, s.cls, s.scale, s.offset_m)) {
            s.mesh_object = std::move(*mesh);
            s.centre_object = box_centre(s.mesh_object);
            ++s.completions;
            ++completed;
        }
    }
    return completed;
}

}  // namespace makeway::pipeline

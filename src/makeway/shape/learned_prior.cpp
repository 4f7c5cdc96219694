#include "makeway/shape/learned_prior.hpp"

#include <limits>

namespace makeway::shape {

LearnedShapePrior::LearnedShapePrior(std::shared_ptr<const ShapeModel> model,
                                     const LearnedPriorParams& params)
    : model_(std::move(model)), params_(params) {}

std::optional<verification::ShapePrior::Estimate> LearnedShapePrior::estimate(
    const std::vector<Eigen::Vector3d>& segment, ObjectClass cls, double floor_z_m) const {
    if (!model_ || shape_class_index(cls) < 0) return std::nullopt;
    // The gravity frame: the floor under the centroid of the points above the ground band.
    std::vector<Eigen::Vector3d> kept;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const auto& p : segment) {
        if (p.z() > floor_z_m + params_.ground_band_m) kept.push_back(p), centroid += p;
    }
    if (kept.size() < params_.min_points) return std::nullopt;
    centroid /= static_cast<double>(kept.size());
    const Eigen::Vector3d origin(centroid.x(), centroid.y(), floor_z_m);
    for (auto& p : kept) p -= origin;
    const auto T = model_->estimate_pose(cls, kept, params_.solve);
    if (!T) return std::nullopt;
    std::vector<Eigen::Vector3d> canonical;
    canonical.reserve(kept.size());
    for (const auto& p : kept) canonical.push_back(T->inverse_apply(p));
    const Completion c =
        complete_shape(*model_, cls, {canonical}, {T->inverse_apply(-origin)}, params_.completion);
    if (c.mesh.triangles.empty()) return std::nullopt;
    // Object frame: the canonical axes, metres, the lowest point on the floor.
    Estimate e;
    e.mesh_object = c.mesh;
    double zmin = std::numeric_limits<double>::infinity();
    for (auto& v : e.mesh_object.vertices_m) {
        v *= static_cast<float>(T->scale);
        zmin = std::min(zmin, static_cast<double>(v.z()));
    }
    for (auto& v : e.mesh_object.vertices_m) v.z() -= static_cast<float>(zmin);
    e.scale = T->scale;
    e.offset_m = Eigen::Vector3d(0, 0, -zmin);
    // s v = p_object + (0, 0, zmin), so p_sensor = origin + s R v + t = origin + t + (0, 0, zmin) +
    // R p_object (R turns about z).
    e.T_sensor_object = Isometry3::Identity();
    e.T_sensor_object.linear() = T->rotation;
    e.T_sensor_object.translation() = origin + T->translation + Eigen::Vector3d(0, 0, zmin);
    return e;
}

std::optional<TriangleMesh> LearnedShapePrior::complete(const std::vector<View>& views,
                                                        ObjectClass cls, double scale,
                                                        const Eigen::Vector3d& offset_m) const {
    if (!model_ || shape_class_index(cls) < 0 || views.empty() || !(scale > 0.0))
        return std::nullopt;
    std::vector<std::vector<Eigen::Vector3d>> canonical;
    std::vector<Eigen::Vector3d> origins;
    std::size_t points = 0;
    for (const View& v : views) {
        std::vector<Eigen::Vector3d> c;
        c.reserve(v.points_object.size());
        // As in estimate(): the returns near the floor are left out.
        for (const auto& p : v.points_object) {
            if (p.z() > params_.ground_band_m) c.push_back((p - offset_m) / scale);
        }
        points += c.size();
        canonical.push_back(std::move(c));
        origins.push_back((v.origin_object - offset_m) / scale);
    }
    if (points < params_.min_points) return std::nullopt;
    Completion c = complete_shape(*model_, cls, canonical, origins, params_.completion);
    if (c.mesh.triangles.empty()) return std::nullopt;
    for (auto& v : c.mesh.vertices_m) v = (scale * v.cast<double>() + offset_m).cast<float>();
    return std::move(c.mesh);
}

}  // namespace makeway::shape

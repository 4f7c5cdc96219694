#include "makeway/labelling/object_rules.hpp"

#include <algorithm>

#include "makeway/common/angles.hpp"
#include "makeway/labelling/dbscan.hpp"

namespace makeway::labelling {
namespace {

// Points within `distance` of the model's surface (finest level) at T_object_world.
std::size_t count_explained(const std::vector<Eigen::Vector3d>& points_world,
                            const verification::CadModel& model, const Isometry3& T_object_world,
                            double distance) {
    std::size_t n = 0;
    double d2 = 0.0;
    for (const Eigen::Vector3d& p : points_world) {
        if (model.levels.back().nearest(T_object_world * p, distance, &d2) !=
            verification::ModelLevel::kNone)
            ++n;
    }
    return n;
}

}  // namespace

std::size_t Cluster::movable_count() const {
    return static_cast<std::size_t>(std::count(movable.begin(), movable.end(), 1));
}

std::vector<Cluster> cluster_points(const std::vector<Eigen::Vector3d>& points_world,
                                    const std::vector<char>& movable, int depth,
                                    const LabelParams& params) {
    std::vector<Eigen::Vector3d> scaled = points_world;
    for (Eigen::Vector3d& q : scaled) q.z() *= params.dbscan_z_scale;
    std::vector<Cluster> out;
    for (const std::vector<std::size_t>& members : cluster_members(dbscan(scaled, params.dbscan))) {
        if (members.size() < params.min_cluster_points) continue;
        Cluster c;
        c.depth = depth;
        for (std::size_t i : members) {
            c.points_world.push_back(points_world[i]);
            c.movable.push_back(movable[i]);
        }
        out.push_back(std::move(c));
    }
    return out;
}

bool furniture_sized(const OrientedBox& box_world, double floor_z, const LabelParams& params) {
    const double height = box_world.z_max_m() - floor_z;
    return height >= params.min_object_height_m && height <= params.max_object_height_m &&
           std::max(box_world.size_m.x(), box_world.size_m.y()) <= params.max_object_length_m;
}

std::optional<std::vector<Eigen::Vector3d>> movable_part(const Cluster& cluster,
                                                         const LabelParams& params) {
    const std::size_t n_movable = cluster.movable_count();
    if (cluster.depth >= params.max_splits || n_movable < params.min_cluster_points ||
        n_movable == cluster.points_world.size()) {
        return std::nullopt;
    }
    std::vector<Eigen::Vector3d> part;
    for (std::size_t i = 0; i < cluster.points_world.size(); ++i) {
        if (cluster.movable[i]) part.push_back(cluster.points_world[i]);
    }
    return part;
}

std::optional<CadFit> fit_cad_model(
    const Cluster& cluster, const OrientedBox& box_world, double floor_z,
    const std::vector<verification::CadLibrary>& one_model_libraries,
    const SeenThrough& seen_through, const LabelParams& params) {
    const std::size_t n = cluster.points_world.size();
    PointCloud cloud;
    for (const Eigen::Vector3d& p : cluster.points_world) cloud.xyz.push_back(p.cast<float>());
    std::optional<CadFit> best;
    for (const verification::CadLibrary& one : one_model_libraries) {
        const verification::CadModel& model = one.models().front();
        for (double turn : {0.0, 0.25 * kPi}) {
            Detection det;
            det.box_sensor = box_world;  // the verifier's frame is its cloud's: here the world
            det.box_sensor.yaw_rad += turn;
            det.cls = model.cls;
            det.class_probabilities.fill(0.0);
            det.class_probabilities[static_cast<std::size_t>(model.cls)] = 1.0;
            verification::VerifiedDetection v =
                verification::verify_detection(cloud, det, one, params.verify, floor_z);
            // Rule 1: a residual the verifier accepts, lower than the best so far.
            if (!v.accepted || (best && v.residual_m >= best->verified.residual_m)) continue;
            // Rule 2: the model explains enough of the cluster (not one leg of a larger object).
            const std::size_t explained = count_explained(
                cluster.points_world, model, v.T_sensor_object.inverse(), params.label_distance_m);
            if (static_cast<double>(explained) < params.min_coverage * static_cast<double>(n) ||
                explained < params.min_object_points)
                continue;
            // Rule 3: where the session's rays passed through the model's surface, the object is
            // not there (a table's top over a chair whose legs it matched, an office chair's
            // armrests on one that has none).
            const double through = seen_through ? seen_through(model, v.T_sensor_object) : 0.0;
            if (through > params.max_seen_through) continue;
            best = CadFit{std::move(v), &model, explained, through};
        }
    }
    return best;
}

std::optional<Cluster> unexplained_rest(const Cluster& cluster, const CadFit& fit,
                                        const LabelParams& params) {
    const Isometry3 T_object_world = fit.verified.T_sensor_object.inverse();
    Cluster rest;
    rest.depth = cluster.depth + 1;
    double d2 = 0.0;
    for (std::size_t i = 0; i < cluster.points_world.size(); ++i) {
        if (fit.model->levels.back().nearest(T_object_world * cluster.points_world[i],
                                             params.split_distance_m,
                                             &d2) != verification::ModelLevel::kNone) {
            continue;
        }
        rest.points_world.push_back(cluster.points_world[i]);
        rest.movable.push_back(cluster.movable[i]);
    }
    const bool split = cluster.depth < params.max_splits &&
                       rest.points_world.size() >= params.min_cluster_points &&
                       static_cast<double>(rest.points_world.size()) >=
                           params.split_share * static_cast<double>(cluster.points_world.size());
    if (!split) return std::nullopt;
    return rest;
}

}  // namespace makeway::labelling

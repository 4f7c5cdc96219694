#pragma once
// Step 5 of the annotation (labeller.hpp), rule by rule: one session's map (world frame) is
// clustered; a furniture-sized cluster gets the CAD model that fits it best under three rules
// (accepted residual, explained share, not seen through), and what that model leaves far from its
// surface is clustered again; a cluster too large for furniture gives up its Movable points. Every
// box and point here is in the session's world frame (the verifier's "sensor" frame is whatever
// frame its cloud is in).
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <vector>

#include "makeway/common/oriented_box.hpp"
#include "makeway/labelling/labeller.hpp"
#include "makeway/verification/cad_library.hpp"
#include "makeway/verification/verifier.hpp"

namespace makeway::labelling {

/// Points of one session's map that may form an object, each Movable (another session saw the
/// space free) or not, and how many times it has been split off a larger cluster.
struct Cluster {
    std::vector<Eigen::Vector3d> points_world;
    std::vector<char> movable;  ///< per point
    int depth = 0;
    std::size_t movable_count() const;
};

/// DBSCAN (heights scaled by dbscan_z_scale first: below 1, vertical gaps count for less, e.g. an
/// office chair's thin column); clusters of at least min_cluster_points, at `depth`.
std::vector<Cluster> cluster_points(const std::vector<Eigen::Vector3d>& points_world,
                                    const std::vector<char>& movable, int depth,
                                    const LabelParams& params);

/// Height above the floor within [min_object_height_m, max_object_height_m] and a footprint no
/// longer than max_object_length_m.
bool furniture_sized(const OrientedBox& box_world, double floor_z, const LabelParams& params);

/// A cluster too large for furniture (a wall with chairs against it): its Movable points, to be
/// clustered again, when there are at least min_cluster_points of them, not all, and the cluster
/// may still be split (depth < max_splits).
std::optional<std::vector<Eigen::Vector3d>> movable_part(const Cluster& cluster,
                                                         const LabelParams& params);

/// A CAD model placed on a cluster.
struct CadFit {
    verification::VerifiedDetection verified;  ///< T_sensor_object and box_sensor: world frame
    const verification::CadModel* model = nullptr;
    std::size_t explained = 0;  ///< cluster points within label_distance_m of its surface
    double seen_through = 0.0;  ///< share of its observed surface the session saw through
};
/// The share of a model's surface (at T_world_object) that the session saw through.
using SeenThrough =
    std::function<double(const verification::CadModel& model, const Isometry3& T_world_object)>;

/// Every model (`one_model_libraries[i]` holds library model i alone), from the cluster's box
/// turned by 0 and 45 deg (the verifier tries the four quarter turns of each: a square footprint's
/// PCA yaw says nothing). A fit counts when the verifier accepts its residual (verify.e_max_m), it
/// explains at least min_coverage of the cluster and min_object_points, and the session saw through
/// at most max_seen_through of its surface (a table's top over a chair whose legs it matched). The
/// lowest residual wins; none: nullopt.
std::optional<CadFit> fit_cad_model(
    const Cluster& cluster, const OrientedBox& box_world, double floor_z,
    const std::vector<verification::CadLibrary>& one_model_libraries,
    const SeenThrough& seen_through, const LabelParams& params);

/// What a fit leaves farther than split_distance_m from its model (another object merged into the
/// cluster: a chair tucked under its table), as a cluster to split again when it is at least
/// split_share of the cluster and min_cluster_points and the cluster may still be split; nearer
/// points are the object's own noise.
std::optional<Cluster> unexplained_rest(const Cluster& cluster, const CadFit& fit,
                                        const LabelParams& params);

}  // namespace makeway::labelling

#pragma once
// Ground plane by RANSAC at start-up (Fischler & Bolles 1981): the plane with the most points,
// among planes tilted at most max_tilt_deg from the sensor's horizontal, refined by least squares
// on its inliers. Then, per keyframe, points near the ground and above the ceiling height are
// removed.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "makeway/common/point_cloud.hpp"

namespace makeway::perception {

struct GroundPlaneParams {
    double inlier_distance_m = 0.05;
    int iterations = 300;
    double max_tilt_deg = 25.0;  ///< the ground is roughly below a robot's sensor
    double voxel_m =
        0.1;  ///< hypotheses are scored by inlier voxels of this size (area); 0: by points
    std::size_t min_inliers =
        200;  ///< inlier voxels (points when voxel_m = 0) for a plane to count
    /// The ground lies at least this far below the sensor. Without it, the returns of the beams
    /// near 0 deg elevation on the walls (the VLP-32C packs 20 of its 32 beams within +-4 deg) form
    /// a "plane" through the sensor that can out-vote the floor in a small room.
    double min_sensor_height_m = 0.15;
    std::uint64_t seed = 0;
    std::vector<std::string> validate() const;
};

struct GroundPlaneResult {
    bool found = false;
    Eigen::Vector3d normal =
        Eigen::Vector3d::UnitZ();  ///< unit, pointing up (away from the ground)
    double offset = 0.0;           ///< plane: normal . p + offset = 0
    std::size_t inliers = 0;
    std::string reason;  ///< why not found

    /// Signed height of p above the plane [m].
    double height_of(const Eigen::Vector3d& p) const { return normal.dot(p) + offset; }
    /// z of the plane below (x, y) [m]: where an object standing there has its origin.
    double floor_z_at(double x_m, double y_m) const {
        return -(normal.x() * x_m + normal.y() * y_m + offset) / normal.z();
    }
    /// (normal, offset) when found: what the detector levels its input with.
    std::optional<Eigen::Vector4d> plane() const {
        if (!found) return std::nullopt;
        return Eigen::Vector4d(normal.x(), normal.y(), normal.z(), offset);
    }
};

GroundPlaneResult fit_ground_plane(const PointCloud& points_sensor,
                                   const GroundPlaneParams& params);

struct GroundFilterParams {
    double ground_band_m = 0.08;    ///< points lower than this above the ground are removed
    double ceiling_height_m = 2.2;  ///< points higher than this above the ground are removed
    std::vector<std::string> validate() const;
};

/// Keeps the points between the ground band and the ceiling height (all channels kept).
PointCloud remove_ground_and_ceiling(const PointCloud& points_sensor,
                                     const GroundPlaneResult& ground,
                                     const GroundFilterParams& params);

}  // namespace makeway::perception

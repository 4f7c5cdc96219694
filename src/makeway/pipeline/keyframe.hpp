#pragma once
// One keyframe preprocessing for everything that reads keyframes (the online pipeline, the
// detector's dataset and evaluation, the verification benchmark, the commands): the ground plane
// by RANSAC unless one is already known, then the ground band and the ceiling removed.
#include <optional>

#include "makeway/common/point_cloud.hpp"
#include "makeway/perception/ground.hpp"
#include "makeway/pipeline/system_params.hpp"

namespace makeway::pipeline {

struct PreparedKeyframe {
    PointCloud cloud_sensor;  ///< ground and ceiling removed (all points when no plane was found)
    perception::GroundPlaneResult ground;
    /// z of the floor below (x, y) in the sensor frame [m]; none without a plane.
    std::optional<double> floor_z_at(double x_m, double y_m) const {
        if (!ground.found) return std::nullopt;
        return ground.floor_z_at(x_m, y_m);
    }
};

/// `known_ground`: a plane fitted before (the sensor is rigid on the robot, so the floor stays put
/// in its frame); refitted when null or not found.
PreparedKeyframe prepare_keyframe(const PointCloud& raw_sensor, const KeyframeParams& params,
                                  const perception::GroundPlaneResult* known_ground = nullptr);

/// The channels a real sensor gives: the simulator's semantic labels and instance ids dropped
/// (moved: the cloud's own; copied: only the sensor's channels are).
PointCloud sensor_channels_only(PointCloud&& cloud);
PointCloud sensor_channels_only(const PointCloud& cloud);

}  // namespace makeway::pipeline

#pragma once
// A chair's yaw from its back rest, for detections no CAD model verifies (a building whose models
// the user does not have). The network's chair yaw is within 30 deg of the truth almost always but
// within 10 deg only four times in five (eval-detection --no-cad): a box fitted to a partial view
// turns with what the sensor saw of it. The back is what a chair shows best: its highest part, a
// plate about as wide as the seat and a few centimetres thick, across the chair's facing. The
// principal axis of the box's highest points gives the facing modulo pi; the network's yaw picks
// the nearer of the two, and the turn is bounded, so a seat seen alone (round: no axis) or a
// table's edge under the box cannot turn a chair around.
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "makeway/common/detection.hpp"
#include "makeway/common/point_cloud.hpp"

namespace makeway::verification {

struct BackYawParams {
    bool enabled = true;
    /// The back: segment points in the top share of the box's height above the floor (a chair's
    /// seat sits at about half its height, arm rests at two thirds).
    double top_share = 0.3;
    double margin_m = 0.05;       ///< the box grown by this on every side cuts the segment
    std::size_t min_points = 20;  ///< fewer back points: the network's yaw stays
    /// Variance along the back's axis over the variance across it, at least (a plate seen from
    /// the front or behind; a back seen edge-on, a stool's round seat: no axis).
    double min_elongation = 6.0;
    double max_turn_rad = 0.6;  ///< larger corrections are not trusted: the network's yaw stays
    std::vector<std::string> validate() const;
};

struct BackYawResult {
    bool refined = false;    ///< the yaw below is the back's
    double yaw_rad = 0.0;    ///< the box's yaw turned by turn_rad (or the box's)
    double turn_rad = 0.0;   ///< the back's axis against the box's y axis, in (-pi/2, pi/2]
    std::size_t points = 0;  ///< back points
    double elongation = 0.0;
};

/// The yaw of a chair box (sensor frame) from the segment's points (sensor frame); floor_z_m: the
/// floor's height under it (none: the box's bottom).
BackYawResult yaw_from_back(const std::vector<Eigen::Vector3d>& segment_sensor,
                            const OrientedBox& box_sensor, std::optional<double> floor_z_m,
                            const BackYawParams& params);

/// The detections with every chair turned to its back's yaw where its back shows one (the others
/// as given): what the map gets when no CAD model verifies them. floor_z_at(x, y): the floor's
/// height under a box (empty, or none: its bottom).
std::vector<Detection> chairs_turned_to_their_backs(
    const PointCloud& cloud_sensor, std::vector<Detection> detections,
    const std::function<std::optional<double>(double, double)>& floor_z_at,
    const BackYawParams& params);

}  // namespace makeway::verification

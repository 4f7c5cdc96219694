#pragma once
// Occlusion by other objects (paper, "Object Tracking"): rays from the sensor to points of an
// object's box tested against the axis-aligned bounding boxes of the other objects.
#include <vector>

#include "makeway/common/oriented_box.hpp"
#include "makeway/common/point_cloud.hpp"
#include "makeway/common/transforms.hpp"

namespace makeway::tracking {

struct OcclusionParams {
    double blocked_fraction = 0.5;  ///< occluded when at least this share of the rays is blocked
    double shrink = 0.8;  ///< ray targets: centre and box corners pulled toward the centre
    // Scan evidence (when the keyframe is given): a ray is blocked by returns in front of the
    // target.
    double scan_bin_deg = 1.0;   ///< azimuth bins of the keyframe [deg]
    double scan_margin_m = 0.3;  ///< returns closer than the target by this much block the ray
    int scan_min_points =
        3;  ///< ... when there are at least this many in the ray's bin and height band
    double scan_floor_clearance_m = 0.15;  ///< the band starts this far above the object's base
};

/// Extension beyond the paper: walls, people and unmapped clutter hide objects too. The keyframe's
/// returns, binned by azimuth, tell whether something stands between the sensor and a point.
class ScanOcclusion {
  public:
    ScanOcclusion(const PointCloud& cloud_sensor, const Isometry3& T_world_sensor,
                  const OcclusionParams& params = {});
    /// Whether returns block the ray to `target_world` within the height band [z_lo, z_hi] (world):
    /// returns nearer than the target by more than clear_m (the object's own extent along the ray)
    /// plus the margin.
    bool blocks(const Eigen::Vector3d& target_world, double z_lo_world, double z_hi_world,
                double clear_m) const;

  private:
    struct Return {
        float range_m, z_m;
    };
    OcclusionParams params_;
    Isometry3 T_sensor_world_;
    double sensor_z_world_ = 0.0;
    std::vector<std::vector<Return>> bins_;
};

/// True when the ray from `from` to `to` passes through the axis-aligned box [lo, hi] strictly
/// between its ends (slab test).
bool ray_hits_aabb(const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                   const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

/// Whether `target` is hidden from `sensor_world` by `others` (which must not contain the target;
/// boxes that contain the sensor are ignored). Targets: the box centre and its 4 footprint corners
/// at mid height, shrunk toward the centre.
/// With `scan`, a ray also counts as blocked when the keyframe has returns in front of the target.
bool is_occluded(const Eigen::Vector3d& sensor_world, const OrientedBox& target,
                 const std::vector<OrientedBox>& others, const OcclusionParams& params = {},
                 const ScanOcclusion* scan = nullptr);

}  // namespace makeway::tracking

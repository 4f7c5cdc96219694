#include "makeway/pipeline/keyframe.hpp"

#include <utility>
#include <vector>

namespace makeway::pipeline {

PreparedKeyframe prepare_keyframe(const PointCloud& raw, const KeyframeParams& params,
                                  const perception::GroundPlaneResult* known_ground) {
    PreparedKeyframe out;
    out.ground = known_ground && known_ground->found
                     ? *known_ground
                     : perception::fit_ground_plane(raw, params.ground);
    out.cloud_sensor = out.ground.found ? perception::remove_ground_and_ceiling(
                                              raw, out.ground, params.ground_filter)
                                        : raw;
    return out;
}

PointCloud sensor_channels_only(PointCloud&& cloud) {
    PointCloud out = std::move(cloud);
    out.label.clear();
    out.instance.clear();
    return out;
}

PointCloud sensor_channels_only(const PointCloud& cloud) {
    static_assert(sizeof(PointCloud) == 6 * sizeof(std::vector<float>),
                  "a new PointCloud channel: copy it here if a sensor gives it");
    PointCloud out;
    out.xyz = cloud.xyz;
    out.intensity = cloud.intensity;
    out.ring = cloud.ring;
    out.time_s = cloud.time_s;
    return out;
}

}  // namespace makeway::pipeline

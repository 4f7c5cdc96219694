#include "makeway/pipeline/keyframe.hpp"

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

PointCloud sensor_channels_only(PointCloud cloud) {
    cloud.label.clear();
    cloud.instance.clear();
    return cloud;
}

}  // namespace makeway::pipeline

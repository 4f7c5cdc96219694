#pragma once
// A keyframe with its labelled chairs and tables: detector training and evaluation data.
#include <optional>
#include <string>
#include <vector>

#include "makeway/common/oriented_box.hpp"
#include "makeway/common/point_cloud.hpp"
#include "makeway/common/semantic_label.hpp"
#include "makeway/common/transforms.hpp"

namespace makeway {

struct LabelledObject {
    std::uint32_t id = 0;  ///< the object's identity across a sequence's keyframes (0: unknown)
    ObjectClass cls = ObjectClass::kChair;
    std::string style;  ///< CAD style name when known (simulated data)
    OrientedBox box_sensor;
    std::size_t points = 0;  ///< keyframe points on the object
};

struct LabelledKeyframe {
    PointCloud cloud_sensor;              ///< ground and ceiling removed
    std::vector<LabelledObject> objects;  ///< seen by enough points to be labelled
    /// Objects in range but seen by too few points (hidden or in shadow): not detectable in this
    /// keyframe, yet an object map that saw them before should still hold them.
    std::vector<LabelledObject> unseen;
    std::uint32_t sequence = 0;  ///< keyframes of one drive share it, stored in time order
    double stamp_s = 0.0;
    Isometry3 T_world_sensor =
        Isometry3::Identity();  ///< the keyframe's pose as the online system estimates it
    /// The front end's ground plane in the sensor frame (normal, offset: n.p + d = 0), when found.
    std::optional<Eigen::Vector4d> ground_plane_sensor;
};

}  // namespace makeway

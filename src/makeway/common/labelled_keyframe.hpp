#pragma once
// A keyframe with its labelled chairs and tables: detector training and evaluation data.
#include <string>
#include <vector>

#include "makeway/common/oriented_box.hpp"
#include "makeway/common/point_cloud.hpp"
#include "makeway/common/semantic_label.hpp"

namespace makeway {

struct LabelledObject {
    ObjectClass cls = ObjectClass::kChair;
    std::string style;       ///< CAD style name when known (simulated data)
    OrientedBox box_sensor;
    std::size_t points = 0;  ///< keyframe points on the object
};

struct LabelledKeyframe {
    PointCloud cloud_sensor;  ///< ground and ceiling removed
    std::vector<LabelledObject> objects;
};

}  // namespace makeway

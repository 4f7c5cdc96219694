#pragma once
// A detector's output in the sensor frame (the paper's x_S): centre, size, yaw, class distribution
// and confidence.
#include <array>

#include "makeway/common/oriented_box.hpp"
#include "makeway/common/semantic_label.hpp"

namespace makeway {

struct Detection {
    OrientedBox box_sensor;
    ObjectClass cls = ObjectClass::kChair;
    std::array<double, kNumObjectClasses> class_probabilities{1.0, 0.0};
    double score = 1.0;  ///< confidence s_c in [0, 1]
};

}  // namespace makeway

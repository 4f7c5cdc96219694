#pragma once
// An object as the rest of the system sees it: from the tracker's object map, or from the
// simulator's ground truth. What the affordance costmap consumes.
#include <cstdint>
#include <vector>

#include "makeway/common/oriented_box.hpp"
#include "makeway/common/polygon2d.hpp"
#include "makeway/common/semantic_label.hpp"

namespace makeway {

struct ObjectEstimate {
    std::uint32_t id = 0;
    ObjectClass cls = ObjectClass::kChair;
    OrientedBox box_world;  ///< yaw = the object's forward (+x) direction
    Eigen::Vector2d velocity_mps = Eigen::Vector2d::Zero();
    double existence = 1.0;  ///< p_exist in [0, 1]
    /// Where its body-height parts stand, world frame (verification::part_outlines of the CAD
    /// model it was last verified against, at that fit moved with the box since); empty when no
    /// CAD model placed it.
    std::vector<Polygon2> parts_world;
};

}  // namespace makeway

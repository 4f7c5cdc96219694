#pragma once
// What verification asks of a learned shape model when no CAD model fits a detection (none of its
// class, none given, or the best fit rejected): a model of this very object, made from its segment.
// makeway::shape answers it with F_n's pose and F_1's completed shape; verification links no torch.
#include <optional>
#include <vector>

#include "makeway/common/semantic_label.hpp"
#include "makeway/common/transforms.hpp"
#include "makeway/common/triangle_mesh.hpp"

namespace makeway::verification {

class ShapePrior {
public:
    virtual ~ShapePrior() = default;
    struct Estimate {
        TriangleMesh mesh_object;  ///< in an object frame: origin on the floor under the shape, x forward, z up
        Isometry3 T_sensor_object = Isometry3::Identity();
    };
    /// From the segment (sensor frame, the floor at floor_z_m under it, the sensor at the origin);
    /// nullopt when no pose or no shape was found. Must be safe to call from several threads.
    virtual std::optional<Estimate> estimate(const std::vector<Eigen::Vector3d>& segment_sensor, ObjectClass cls, double floor_z_m) const = 0;
};

}  // namespace makeway::verification

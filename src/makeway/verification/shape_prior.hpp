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
        TriangleMesh mesh_object;  ///< in an object frame: origin on the floor under the shape, x
                                   ///< forward, z up
        Isometry3 T_sensor_object = Isometry3::Identity();
        /// The object frame from the prior's own (canonical) frame: p_object = scale p_canonical +
        /// offset_m. complete() takes views in the object frame and hands them back through it.
        double scale = 1.0;
        Eigen::Vector3d offset_m = Eigen::Vector3d::Zero();
    };
    /// One observation of an object in its object frame: its returns and the sensor's origin.
    struct View {
        std::vector<Eigen::Vector3d> points_object;
        Eigen::Vector3d origin_object = Eigen::Vector3d::Zero();
    };
    /// From the segment (sensor frame, the floor at floor_z_m under it, the sensor at the origin);
    /// nullopt when no pose or no shape was found. Must be safe to call from several threads.
    virtual std::optional<Estimate> estimate(const std::vector<Eigen::Vector3d>& segment_sensor,
                                             ObjectClass cls, double floor_z_m) const = 0;
    /// The shape completed from several views of one object, all in the object frame of an
    /// earlier estimate() (its scale and offset_m); the mesh in that frame. nullopt: no shape, or a
    /// prior that cannot fuse views (the default), whose first shape then stays.
    virtual std::optional<TriangleMesh> complete(const std::vector<View>& /*views*/,
                                                 ObjectClass /*cls*/, double /*scale*/,
                                                 const Eigen::Vector3d& /*offset_m*/) const {
        return std::nullopt;
    }
};

/// The model name verification gives a fit against a shape prior's mesh.
inline constexpr const char* kCompletedShapeModel = "completed shape";

}  // namespace makeway::verification

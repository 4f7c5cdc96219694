#pragma once
// Placing a CAD mesh from another tool in makeway's object frame (origin at the centre of the
// footprint on the floor, z up, x forward): authors draw furniture Y-up or Z-up, facing any axis,
// in metres, centimetres or inches, about any origin. A scene or furniture index says which; this
// turns, scales and re-centres the mesh, and says when the result cannot be a chair or a table.
#include <optional>
#include <string>
#include <string_view>

#include "makeway/common/semantic_label.hpp"
#include "makeway/common/transforms.hpp"
#include "makeway/common/triangle_mesh.hpp"

namespace makeway {

enum class MeshAxis : std::uint8_t { kPosX, kNegX, kPosY, kNegY, kPosZ, kNegZ };
/// "x", "+x", "-x", ... (case-insensitive).
std::optional<MeshAxis> parse_mesh_axis(std::string_view name);
std::string_view to_string(MeshAxis axis);
Eigen::Vector3d axis_vector(MeshAxis axis);
/// Metres per unit of "m", "cm", "mm", "in", "ft".
std::optional<double> parse_length_unit(std::string_view name);

struct MeshPlacement {
    MeshAxis up = MeshAxis::kPosZ;  ///< the mesh's up, turned to +z
    MeshAxis forward =
        MeshAxis::kPosX;   ///< the mesh's front (a chair: where a sitter faces), turned to +x
    double scale = 1.0;    ///< metres per mesh unit
    bool recentre = true;  ///< footprint centre to the origin, lowest point to z = 0
};

/// The rotation taking `up` to +z and `forward` to +x; nullopt when they are parallel.
std::optional<Eigen::Matrix3d> placement_rotation(MeshAxis up, MeshAxis forward);

/// Throws std::invalid_argument when up and forward are parallel or the scale is not positive.
TriangleMesh place_mesh(TriangleMesh mesh, const MeshPlacement& placement);

/// A warning when a placed mesh's extent cannot be a piece of furniture of `cls` (a chair 12 m
/// tall: wrong units; 0.1 m tall and 0.9 m deep: lying on its side), nullopt when plausible.
std::optional<std::string> implausible_furniture_extent(const TriangleMesh& mesh_object,
                                                        ObjectClass cls);

}  // namespace makeway

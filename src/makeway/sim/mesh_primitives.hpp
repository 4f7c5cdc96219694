#pragma once
// Closed triangle-mesh primitives the CAD generators and scenes are built from. Every primitive is
// appended to an existing mesh, outward-facing (counter-clockwise seen from outside).
#include "makeway/common/transforms.hpp"
#include "makeway/common/triangle_mesh.hpp"

namespace makeway::sim {

/// Box of `size_m` centred at `centre_m`, turned by yaw_rad about z.
void add_box(TriangleMesh& mesh, const Eigen::Vector3d& centre_m, const Eigen::Vector3d& size_m,
             double yaw_rad = 0.0);

/// Box with its long axis from `a_m` to `b_m` and a square cross-section of side `thickness_m`
/// (legs, struts, star-base arms).
void add_strut(TriangleMesh& mesh, const Eigen::Vector3d& a_m, const Eigen::Vector3d& b_m,
               double thickness_m);

/// Upright cylinder (closed), base centre at `base_m`.
void add_cylinder(TriangleMesh& mesh, const Eigen::Vector3d& base_m, double radius_m,
                  double height_m, int segments = 24);

/// UV sphere.
void add_sphere(TriangleMesh& mesh, const Eigen::Vector3d& centre_m, double radius_m,
                int segments = 16);

/// Applies T to every vertex.
void transform_mesh(TriangleMesh& mesh, const Isometry3& T);

/// Total surface area [m^2].
double surface_area_m2(const TriangleMesh& mesh);

}  // namespace makeway::sim

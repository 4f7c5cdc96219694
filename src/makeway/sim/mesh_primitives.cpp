#include "makeway/sim/mesh_primitives.hpp"

#include <array>
#include <cmath>

#include "makeway/common/angles.hpp"

namespace makeway::sim {
namespace {

int add_vertex(TriangleMesh& mesh, const Eigen::Vector3d& p) {
    mesh.vertices_m.push_back(p.cast<float>());
    return static_cast<int>(mesh.vertices_m.size()) - 1;
}

// Eight corners (bottom ring then top ring, counter-clockwise from above) -> 12 triangles.
void add_hexahedron(TriangleMesh& mesh, const std::array<Eigen::Vector3d, 8>& c) {
    const int o = static_cast<int>(mesh.vertices_m.size());
    for (const auto& p : c) add_vertex(mesh, p);
    const int quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                             {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    for (const auto& q : quads) {
        mesh.triangles.emplace_back(o + q[0], o + q[1], o + q[2]);
        mesh.triangles.emplace_back(o + q[0], o + q[2], o + q[3]);
    }
}

}  // namespace

void add_box(TriangleMesh& mesh, const Eigen::Vector3d& centre_m, const Eigen::Vector3d& size_m,
             double yaw_rad) {
    const Isometry3 T = make_T_xyz_yaw(centre_m, yaw_rad);
    const Eigen::Vector3d h = 0.5 * size_m;
    std::array<Eigen::Vector3d, 8> c;
    const double sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
    for (int i = 0; i < 4; ++i) {
        c[i] = T * Eigen::Vector3d(sx[i] * h.x(), sy[i] * h.y(), -h.z());
        c[i + 4] = T * Eigen::Vector3d(sx[i] * h.x(), sy[i] * h.y(), h.z());
    }
    add_hexahedron(mesh, c);
}

void add_strut(TriangleMesh& mesh, const Eigen::Vector3d& a_m, const Eigen::Vector3d& b_m,
               double thickness_m) {
    const Eigen::Vector3d axis = b_m - a_m;
    const double length = axis.norm();
    if (length <= 0.0) return;
    // Frame with z along the strut.
    const Eigen::Vector3d z = axis / length;
    const Eigen::Vector3d helper =
        std::abs(z.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
    const Eigen::Vector3d x = helper.cross(z).normalized();
    const Eigen::Vector3d y = z.cross(x);
    const double h = 0.5 * thickness_m;
    std::array<Eigen::Vector3d, 8> c;
    const double sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
    for (int i = 0; i < 4; ++i) {
        const Eigen::Vector3d off = sx[i] * h * x + sy[i] * h * y;
        c[i] = a_m + off;
        c[i + 4] = b_m + off;
    }
    add_hexahedron(mesh, c);
}

void add_cylinder(TriangleMesh& mesh, const Eigen::Vector3d& base_m, double radius_m,
                  double height_m, int segments) {
    const int bottom_centre = add_vertex(mesh, base_m);
    const int top_centre = add_vertex(mesh, base_m + Eigen::Vector3d(0, 0, height_m));
    const int ring = static_cast<int>(mesh.vertices_m.size());
    for (int i = 0; i < segments; ++i) {
        const double a = 2.0 * kPi * i / segments;
        const Eigen::Vector3d p =
            base_m + radius_m * Eigen::Vector3d(std::cos(a), std::sin(a), 0.0);
        add_vertex(mesh, p);
        add_vertex(mesh, p + Eigen::Vector3d(0, 0, height_m));
    }
    for (int i = 0; i < segments; ++i) {
        const int b0 = ring + 2 * i, t0 = b0 + 1;
        const int b1 = ring + 2 * ((i + 1) % segments), t1 = b1 + 1;
        mesh.triangles.emplace_back(bottom_centre, b1, b0);
        mesh.triangles.emplace_back(top_centre, t0, t1);
        mesh.triangles.emplace_back(b0, b1, t1);
        mesh.triangles.emplace_back(b0, t1, t0);
    }
}

void add_sphere(TriangleMesh& mesh, const Eigen::Vector3d& centre_m, double radius_m,
                int segments) {
    const int rings = segments / 2;
    const int o = static_cast<int>(mesh.vertices_m.size());
    for (int r = 0; r <= rings; ++r) {
        const double polar = kPi * r / rings;
        for (int s = 0; s < segments; ++s) {
            const double az = 2.0 * kPi * s / segments;
            add_vertex(mesh, centre_m + radius_m * Eigen::Vector3d(std::sin(polar) * std::cos(az),
                                                                   std::sin(polar) * std::sin(az),
                                                                   std::cos(polar)));
        }
    }
    for (int r = 0; r < rings; ++r) {
        for (int s = 0; s < segments; ++s) {
            const int a = o + r * segments + s, b = o + r * segments + (s + 1) % segments;
            const int c = a + segments, d = b + segments;
            if (r > 0) mesh.triangles.emplace_back(a, c, b);
            if (r < rings - 1) mesh.triangles.emplace_back(b, c, d);
        }
    }
}

void transform_mesh(TriangleMesh& mesh, const Isometry3& T) {
    const Eigen::Isometry3f Tf = T.cast<float>();
    for (auto& v : mesh.vertices_m) v = Tf * v;
}

double surface_area_m2(const TriangleMesh& mesh) {
    double area = 0.0;
    for (const auto& t : mesh.triangles) {
        const Eigen::Vector3d a = mesh.vertices_m[t[0]].cast<double>();
        const Eigen::Vector3d b = mesh.vertices_m[t[1]].cast<double>();
        const Eigen::Vector3d c = mesh.vertices_m[t[2]].cast<double>();
        area += 0.5 * (b - a).cross(c - a).norm();
    }
    return area;
}

}  // namespace makeway::sim

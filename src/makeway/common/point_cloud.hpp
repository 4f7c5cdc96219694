#pragma once
// Point cloud as contiguous per-field arrays. The frame is carried by the variable name
// (points_sensor, points_world). Optional channels are either empty or hold one value per point.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace makeway {

/// Which optional channels a cloud carries.
struct PointFields {
    bool intensity = false;
    bool ring = false;
    bool time = false;
    bool label = false;
    bool instance = false;

    bool operator==(const PointFields& o) const {  // spelled out: C++17-clean for the ROS 1 files
        return intensity == o.intensity && ring == o.ring && time == o.time && label == o.label &&
               instance == o.instance;
    }
    static PointFields all() { return {true, true, true, true, true}; }
};

struct PointCloud {
    std::vector<Eigen::Vector3f> xyz;     ///< positions [m]
    std::vector<float> intensity;         ///< return strength, sensor units
    std::vector<std::uint16_t> ring;      ///< laser (beam) index
    std::vector<float> time_s;            ///< time since the start of the sweep [s]
    std::vector<std::uint8_t> label;      ///< SemanticLabel value
    std::vector<std::uint32_t> instance;  ///< object instance id, 0 = none

    std::size_t size() const { return xyz.size(); }
    bool empty() const { return xyz.empty(); }
    PointFields fields() const;

    /// Resizes every channel present in `fields` to `n` (value-initialised) and clears the others.
    void resize(std::size_t n, PointFields fields);

    /// Empty string when every present channel has one value per point, else what is wrong.
    std::string consistency_error() const;

    /// Number of points with a NaN or infinite coordinate.
    std::size_t count_non_finite() const;

    /// The points at `indices`, every channel kept.
    PointCloud select(const std::vector<std::size_t>& indices) const;

    /// Appends `other`; both clouds must carry the same channels (checked, throws on mismatch).
    void append(const PointCloud& other);
    /// Room for `n` points in every channel present in `fields` (appending that many then copies
    /// each channel once, with no reallocation).
    void reserve(std::size_t n, PointFields fields);

    /// Positions mapped through T (e.g. T_world_sensor * points_sensor); channels kept.
    PointCloud transformed(const Eigen::Isometry3d& T) const;
};

/// Axis-aligned bounds of the finite points; `valid` is false when there are none.
struct PointBounds {
    bool valid = false;
    Eigen::Vector3f min_m = Eigen::Vector3f::Zero();
    Eigen::Vector3f max_m = Eigen::Vector3f::Zero();
};
PointBounds compute_bounds(const PointCloud& cloud);

/// Keeps only the points with finite coordinates.
PointCloud remove_non_finite(const PointCloud& cloud);

}  // namespace makeway

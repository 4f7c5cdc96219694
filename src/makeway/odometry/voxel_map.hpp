#pragma once
// The odometry's local map: points in a hash of voxels (at most `max_points_per_voxel` each, as
// KISS-ICP keeps them), each voxel with the plane its points span once there are enough of them.
// Registration asks for the nearest point among the 27 voxels around a query and uses its voxel's
// plane: point-to-plane where the map is flat (walls, furniture faces), point-to-point elsewhere.
#include <tsl/robin_map.h>

#include <Eigen/Core>
#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

namespace makeway::odometry {

struct VoxelMapParams {
    double voxel_m = 0.25;
    int max_points_per_voxel = 20;
    int min_points_for_plane = 5;
    /// A voxel's points are a plane when the smallest spread is below this share of the middle
    /// one, and a line when the middle spread is below this share of the largest.
    double planarity = 0.3;
};

/// What a voxel's points look like: a plane (a wall, a table top), a line (a chair or table leg,
/// a door frame, one scan ring on a wall, the edge of a ceiling), a blob (clutter, a corner where
/// planes meet), or too few to say.
enum class VoxelShape { kUnknown, kPlane, kLine, kBlob };

struct MapMatch {
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
    VoxelShape shape = VoxelShape::kUnknown;
    Eigen::Vector3d axis =
        Eigen::Vector3d::Zero();  ///< unit: the normal of a kPlane, the direction of a kLine
    double distance_m = 0.0;
};

class VoxelMap {
  public:
    explicit VoxelMap(const VoxelMapParams& params = {}) : params_(params) {}

    /// Adds world points (voxels already full keep what they have: the map does not drift with new
    /// points). Planes of the voxels that changed are refitted.
    void add(const std::vector<Eigen::Vector3d>& points_world);
    /// Drops voxels farther than `radius_m` from `centre` (horizontal distance).
    void keep_within(const Eigen::Vector3d& centre, double radius_m);
    /// The nearest map point within `max_distance_m` among the 27 voxels around `query`.
    std::optional<MapMatch> nearest(const Eigen::Vector3d& query, double max_distance_m) const;

    bool empty() const { return voxels_.empty(); }
    std::size_t num_voxels() const { return voxels_.size(); }
    std::size_t num_points() const;
    /// Every point of the map (tests, pictures).
    std::vector<Eigen::Vector3d> points() const;

  private:
    struct Voxel {
        Eigen::Vector3d first = Eigen::Vector3d::Zero();  ///< its first point, inline: keep_within
                                                          ///< reads it for every voxel
        std::vector<Eigen::Vector3d> points;
        Eigen::Vector3f low = Eigen::Vector3f::Constant(
            std::numeric_limits<float>::infinity());  ///< the points' box, rounded outward
        Eigen::Vector3f high = -low;
        VoxelShape shape = VoxelShape::kUnknown;
        Eigen::Vector3d axis = Eigen::Vector3d::Zero();
    };
    struct KeyHash {
        std::size_t operator()(const Eigen::Vector3i& k) const {
            return static_cast<std::size_t>(k.x()) * 73856093u ^
                   static_cast<std::size_t>(k.y()) * 19349669u ^
                   static_cast<std::size_t>(k.z()) * 83492791u;
        }
    };
    Eigen::Vector3i key(const Eigen::Vector3d& p) const;
    void fit_plane(Voxel& v) const;

    VoxelMapParams params_;
    tsl::robin_map<Eigen::Vector3i, Voxel, KeyHash> voxels_;
};

}  // namespace makeway::odometry

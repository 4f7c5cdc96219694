#pragma once
// Learned shapes kept per tracked object (supplementary, F_1 "over keyframes"): the first time an
// object is verified against a shape prior's completed mesh, its segment becomes the first view of
// that object, in the object frame the fit found; every later keyframe that verifies it again adds
// a view, and the shape is completed anew from all of them (one TSDF, more of the object seen).
// Verification then asks this class instead of the prior: a segment where a shaped track stands
// gets that track's mesh at its last pose (ICP refines it like a CAD model), and only objects
// without a shape yet go to the prior's per-keyframe pose and completion.
//
// It is a ShapePrior itself, so verification does not change: begin_keyframe() before
// verify_detections(), add_views() after the object map's update.
#include <cstdint>
#include <deque>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "makeway/common/point_cloud.hpp"
#include "makeway/verification/verifier.hpp"

namespace makeway::pipeline {

struct TrackedShapeParams {
    /// A segment whose centroid (xy, points above the floor band) lies this close to a shaped
    /// track's mesh centre is that object. Wider than a chair's half width would let a neighbour
    /// in.
    double match_distance_m = 0.35;
    std::size_t max_views =
        8;  ///< the latest views of an object that are fused (older ones drop out)
    double ground_band_m =
        0.05;  ///< returns this close to the floor are not a view's (nor the centroid's)
    double view_margin_m =
        0.10;  ///< a view is the keyframe's points in the fitted box grown by this
    std::vector<std::string> validate() const;
};

class TrackedShapes : public verification::ShapePrior {
  public:
    /// `prior` (not null, outlives this) gives the first shape of each object and fuses the views.
    explicit TrackedShapes(const verification::ShapePrior* prior,
                           const TrackedShapeParams& params = {});

    /// The keyframe's pose, before verification (estimate() matches segments in the world frame).
    void begin_keyframe(const Isometry3& T_world_sensor) { T_world_sensor_ = T_world_sensor; }

    /// A shaped track's mesh where the segment stands, else the prior's estimate. Thread-safe
    /// between begin_keyframe() and add_views() (reads only).
    std::optional<Estimate> estimate(const std::vector<Eigen::Vector3d>& segment_sensor,
                                     ObjectClass cls, double floor_z_m) const override;

    /// After tracking: `verified` as verification returned them, `track_of_accepted` the object
    /// map's track per accepted detection (TrackerFrameResult::track_of_detection, in order),
    /// `live` the map's tracks now. Each accepted fit against a completed shape adds a view to its
    /// track and completes the track's shape again; shapes of tracks that left the map are dropped.
    /// Returns how many shapes were completed.
    std::size_t add_views(const PointCloud& cloud_sensor,
                          const std::vector<verification::VerifiedDetection>& verified,
                          const std::vector<int>& track_of_accepted,
                          const std::unordered_set<std::uint32_t>& live);

    struct Shape {
        ObjectClass cls = ObjectClass::kChair;
        TriangleMesh mesh_object;
        Isometry3 T_world_object = Isometry3::Identity();         ///< the last verified pose
        Eigen::Vector3d centre_object = Eigen::Vector3d::Zero();  ///< the mesh's box centre
        double scale = 1.0;
        Eigen::Vector3d offset_m = Eigen::Vector3d::Zero();
        std::deque<View> views;
        std::size_t completions = 0;  ///< how often the shape was completed from its views
    };
    const std::unordered_map<std::uint32_t, Shape>& shapes() const { return shapes_; }

  private:
    const verification::ShapePrior* prior_;
    TrackedShapeParams params_;
    Isometry3 T_world_sensor_ = Isometry3::Identity();
    std::unordered_map<std::uint32_t, Shape> shapes_;
};

}  // namespace makeway::pipeline

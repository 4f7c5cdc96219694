#pragma once
// The object map (paper, "Object Tracking"): detections associated with tracked objects by 3D GIoU
// and the Hungarian algorithm, a box Kalman filter per object, class distributions and existence
// probabilities fused by averaging (eqs. 3-5), occluded objects not penalised, and objects removed
// after repeated unexplained misses or when their existence falls below 0.5.
#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "makeway/common/detection.hpp"
#include "makeway/common/object_estimate.hpp"
#include "makeway/common/transforms.hpp"
#include "makeway/tracking/box_kalman_filter.hpp"
#include "makeway/tracking/occlusion.hpp"

namespace makeway::tracking {

struct TrackerParams {
    KalmanParams kalman;
    OcclusionParams occlusion;
    double min_giou = -0.1;          ///< associated pairs need at least this 3D GIoU
    double sensor_range_m = 10.0;    ///< objects farther from the sensor are neither matched nor penalised
    /// Unmatched objects farther than this are not penalised either: where the detector cannot see
    /// (its grid's reach), a miss says nothing. 0: sensor_range_m.
    double miss_range_m = 0.0;
    /// Pairs whose footprints (circumscribed circles) are farther apart than this are not scored:
    /// at 1 m even two 1.8 m tables have a GIoU near -0.2, below any sensible min_giou.
    double association_gate_m = 1.0;
    int min_hits = 2;                ///< detections before an object enters the map's output
    int max_misses = 10;             ///< consecutive unexplained misses that remove an object
    double min_existence = 0.5;      ///< fused existence below this removes an object ...
    int existence_grace_frames = 3;  ///< ... once it has been judged on this many frames
    std::vector<std::string> validate() const;
};

/// One tracked object.
struct Track {
    std::uint32_t id = 0;
    BoxKalmanFilter filter;
    Isometry3 T_world_object_birth = Isometry3::Identity();  ///< the object's own frame, anchored at birth
    std::array<double, kNumObjectClasses> class_probability_sum{};  ///< eq. (3): sum over the k frames
    int class_frames = 0;
    double existence_sum = 0.0;      ///< over frames where the object was visible and in range
    int existence_frames = 0;
    int hits = 0;
    int misses = 0;                  ///< consecutive unexplained misses
    int age_frames = 0;
    double last_stamp_s = 0.0;

    ObjectClass cls() const;                                        ///< eq. (4)
    double class_confidence() const;                                ///< eq. (5)
    std::array<double, kNumObjectClasses> class_distribution() const;  ///< eq. (3)
    double existence() const;
    bool confirmed(int min_hits) const { return hits >= min_hits; }
};

/// What one update did, for diagnostics and evaluation.
struct TrackerFrameResult {
    std::vector<int> track_of_detection;       ///< track id per detection (new or matched; -1: out of range or invalid)
    std::vector<std::uint32_t> born, removed, occluded;
    std::vector<ObjectEstimate> objects_world;  ///< the confirmed map after the update
};

class ObjectMap {
public:
    explicit ObjectMap(const TrackerParams& params = {}) : params_(params) {}

    /// One keyframe: detections in the sensor frame, the sensor pose, the keyframe's time.
    /// Detection scores are the per-frame existence evidence (verified p_exist where available).
    /// With the keyframe cloud (sensor frame), returns in front of an object also count as occlusion.
    TrackerFrameResult update(const std::vector<Detection>& detections_sensor, const Isometry3& T_world_sensor, double stamp_s,
                              const PointCloud* keyframe_sensor = nullptr);

    /// Confirmed objects, world frame.
    std::vector<ObjectEstimate> objects() const;
    const std::unordered_map<std::uint32_t, Track>& tracks() const { return tracks_; }
    const TrackerParams& params() const { return params_; }

private:
    TrackerParams params_;
    std::unordered_map<std::uint32_t, Track> tracks_;
    std::uint32_t next_id_ = 1;
    bool started_ = false;
    double last_stamp_s_ = 0.0;
};

}  // namespace makeway::tracking

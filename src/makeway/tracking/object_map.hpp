#pragma once
// The object map (paper, "Object Tracking"): detections associated with tracked objects by 3D GIoU
// and the Hungarian algorithm, a box Kalman filter per object, class distributions and existence
// probabilities fused by averaging (eqs. 3-5), occluded objects not penalised, and objects removed
// after repeated unexplained misses or when their existence falls below 0.5.
//
// The lifecycle beyond the paper, so that no object outlives its evidence: a velocity is believed
// only while observed (MotionPrior), an object out of range is frozen or dropped (OutOfRange), any
// object unobserved for max_unobserved_s leaves, detections off the floor are not used, and two
// confirmed objects on one footprint are merged.
#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "makeway/common/detection.hpp"
#include "makeway/common/object_estimate.hpp"
#include "makeway/common/transforms.hpp"
#include "makeway/tracking/box_kalman_filter.hpp"
#include "makeway/tracking/occlusion.hpp"

namespace makeway::tracking {

/// What a class's objects do between observations. Furniture stands on the floor and is still
/// most of the time; it moves only while someone pushes it, and then it is being observed or it
/// soon will be. A velocity estimate is therefore believed only while measurements support it:
/// without them it decays toward zero, so a track that stops being detected stays near where it
/// was last seen instead of drifting away (through a wall) at its last speed.
struct MotionPrior {
    /// Time constant of the velocity's decay while unobserved [s]: v <- v exp(-dt / tau).
    /// 0: zeroed at the first unobserved frame; infinity: kept (constant velocity, as AB3DMOT).
    double velocity_decay_s = 0.5;
    double max_speed_mps = 1.5;  ///< horizontal speed estimates are clamped to this
    bool planar = true;  ///< no vertical motion (vz held at 0): things that stand on a floor
    /// Static until it moved: the object is held at rest (velocity 0) unless its detections within
    /// the last motion_window_s (spanning at least half of it) moved it at least this far, and then
    /// its velocity is the least-squares slope of those detections (the filter's velocity, driven
    /// by the last few boxes of partial views, overshoots). Detection noise otherwise reads as
    /// motion. 0: the filter's velocity, always free (traffic).
    double min_displacement_m = 0.3;
    double motion_window_s = 2.0;
    /// An object at rest does not turn either: its yaw random walk is this instead of the
    /// filter's (KalmanParams::yaw_rate_sigma_radps, which follows a pushed chair), so the map's
    /// yaw averages the views of a standing chair instead of repeating the last box's. The
    /// network's yaw is within 10 deg of the truth for three chairs in four, and its errors
    /// change with the view (eval-detection --no-cad). The pipeline keeps the filter's own where
    /// CAD models verify the boxes (pipeline::tracker_params_for).
    double rest_yaw_rate_sigma_radps = 0.03;
    /// ... unless it is turned where it stands: two detections in a row whose yaw differs from the
    /// object's by more than this, the same way, give the yaw the filter's full random walk for
    /// that frame. Single outliers of the network do not.
    double turn_release_rad = 0.3;
    std::vector<std::string> validate() const;
};

/// What happens to a track whose predicted box leaves the sensor range: nothing can confirm or
/// refute it there. kFreeze keeps it where it was last believed, velocity zero (a map remembers the
/// room behind the robot); kDrop removes it (a tracker of traffic, whose objects do not come back).
enum class OutOfRange { kFreeze, kDrop };

/// How detection scores become existence evidence in [0, 1]: as they are (probabilities), or
/// through the logistic function (raw logits, as many detectors write them).
enum class ScoreTransform { kNone, kSigmoid };

struct TrackerParams {
    KalmanParams kalman;
    OcclusionParams occlusion;
    /// Indexed by ObjectClass (chair, table). Chairs roll or are carried at up to a brisk walk;
    /// tables are heavy, dragged at a slow walk, and their boxes shift more with the view (half a
    /// table's length), so they need a larger displacement over a longer window before they move.
    std::array<MotionPrior, kNumObjectClasses> motion{MotionPrior{0.5, 1.5, true, 0.3, 2.0},
                                                      MotionPrior{0.5, 0.5, true, 0.6, 3.0}};
    std::array<bool, kNumObjectClasses> tracked_classes{
        true, true};  ///< detections of other classes are not used
    ScoreTransform score_transform = ScoreTransform::kNone;
    double min_score = 0.0;  ///< detections scoring below this (after the transform) are not used
    double min_giou = -0.1;  ///< associated pairs need at least this 3D GIoU ...
    /// ... or, when > 0, pairs are scored by the distance between their centres instead of GIoU
    /// and need at most this (thin boxes like cyclists overlap little from frame to frame).
    double max_centre_distance_m = 0.0;
    double sensor_range_m =
        10.0;  ///< objects farther from the sensor are neither matched nor penalised
    OutOfRange out_of_range = OutOfRange::kFreeze;
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
    /// A robot standing still sees the same frame again and again: the detector's and the
    /// verifier's errors repeat with it, so repeated frames are not independent evidence. Frames
    /// that see an object from about the same place (the sensor's offset from the object, world
    /// x-y, within same_view_m of the view's first frame) within same_view_period_s are one view:
    /// the object's existence averages views (each view's mean evidence), and a view counts at
    /// most one miss. So a chair watched by a still robot keeps the existence its earlier views
    /// gave it, and a chair taken away while the robot watches leaves by time (a view every
    /// same_view_period_s) instead of by frame rate. 0: every frame is a view (the paper's eq.).
    double same_view_m = 0.25;
    double same_view_period_s = 2.0;
    /// Any object not associated with a detection for this long leaves the map, wherever it is
    /// (occluded, out of range): memory of an unseen room expires. Infinity: never.
    double max_unobserved_s = 60.0;
    /// With a floor plane given: detections whose box bottom is farther than this from the floor
    /// are not used (a chair-sized box on a table top is a part of the table, or a chair on it
    /// that nobody will walk into). Infinity: no floor prior.
    double max_floor_gap_m = 0.3;
    /// Two confirmed objects of one class whose footprints overlap by more than this (BEV IoU) are
    /// one object seen twice: the one with fewer detections is removed. 1: never merge.
    double merge_iou = 0.4;
    /// A detection is associated only if its centre lies within the distance the object could
    /// have moved (its class's max_speed_mps x dt) plus this many standard deviations of the
    /// predicted position and the measurement. Without it a false positive up to the association
    /// gate away drags a standing chair at metres per second.
    double motion_gate_sigma = 3.0;
    std::vector<std::string> validate() const;
};

/// Settings for traffic seen from a moving car without ego-motion (KITTI's camera frame): parked
/// cars move at the car's speed, nothing stands on a known floor, objects leave for good. Per KITTI
/// type ("Car", "Pedestrian", "Cyclist", any case; others get Car's), chosen on the KITTI tracking
/// training sequences with PointRCNN's detections (README, "Tracking on KITTI").
TrackerParams traffic_preset(std::string_view type);

/// One tracked object.
struct Track {
    std::uint32_t id = 0;
    BoxKalmanFilter filter;
    Isometry3 T_world_object_birth =
        Isometry3::Identity();  ///< the object's own frame, anchored at birth
    std::array<double, kNumObjectClasses>
        class_probability_sum{};  ///< eq. (3): sum over the k frames
    int class_frames = 0;
    double existence_sum = 0.0;  ///< over closed views where the object was visible and in range
    int existence_views = 0;     ///< closed views (TrackerParams::same_view_m)
    int existence_frames = 0;    ///< frames judged (existence_grace_frames)
    /// The open view: evidence summed over its frames, where it was seen from, when it began,
    /// whether it counted a miss.
    double view_sum = 0.0;
    int view_frames = 0;
    Eigen::Vector2d view_offset = Eigen::Vector2d::Zero();
    double view_start_s = 0.0;
    bool view_missed = false;
    int hits = 0;
    int misses = 0;  ///< consecutive unexplained misses
    int age_frames = 0;
    double last_stamp_s = 0.0;
    std::deque<std::pair<double, Eigen::Vector2d>>
        seen_at;          ///< (stamp, centre) of recent detections
    bool at_rest = true;  ///< held at rest by its MotionPrior (no window fit moved it)
    int turn_sign = 0;    ///< the sign of the last yaw innovation beyond turn_release_rad, or 0

    ObjectClass cls() const;                                           ///< eq. (4)
    double class_confidence() const;                                   ///< eq. (5)
    std::array<double, kNumObjectClasses> class_distribution() const;  ///< eq. (3)
    double existence() const;  ///< the mean over views, the open one included
    int views() const { return existence_views + (view_frames > 0 ? 1 : 0); }
    bool confirmed(int min_hits) const { return hits >= min_hits; }
};

/// What one update did, for diagnostics and evaluation.
struct TrackerFrameResult {
    std::vector<int> track_of_detection;  ///< track id per detection (new or matched; -1: out of
                                          ///< range or invalid)
    std::vector<std::uint32_t> born, removed, occluded;
    std::vector<std::uint32_t> frozen;  ///< out of range and held in place this frame
    std::size_t unused_detections =
        0;  ///< below min_score, untracked class, out of range, invalid or off the floor
    std::vector<ObjectEstimate> objects_world;  ///< the confirmed map after the update
};

class ObjectMap {
  public:
    explicit ObjectMap(const TrackerParams& params = {}) : params_(params) {}

    /// One keyframe: detections in the sensor frame, the sensor pose, the keyframe's time.
    /// Detection scores are the per-frame existence evidence (verified p_exist where available).
    /// With the keyframe cloud (sensor frame), returns in front of an object also count as
    /// occlusion. With the floor plane (world frame, n . p + d = 0, n up), detections must stand on
    /// it. Throws std::invalid_argument when stamp_s goes back in time or a score is not in [0, 1]
    /// after the score transform (never clamped: a logit read as a probability is a setup error).
    TrackerFrameResult update(const std::vector<Detection>& detections_sensor,
                              const Isometry3& T_world_sensor, double stamp_s,
                              const PointCloud* keyframe_sensor = nullptr,
                              const Eigen::Vector4d* floor_plane_world = nullptr);

    /// Where objects can stand (world x, y), e.g. the free space of the prebuilt map of walls:
    /// detections centred elsewhere are not used and objects predicted elsewhere leave. Default:
    /// anywhere.
    void set_region(std::function<bool(const Eigen::Vector2d&)> allowed) {
        region_ = std::move(allowed);
    }

    /// Confirmed objects, world frame.
    std::vector<ObjectEstimate> objects() const;
    const std::unordered_map<std::uint32_t, Track>& tracks() const { return tracks_; }
    const TrackerParams& params() const { return params_; }

  private:
    std::vector<bool> usable_detections(const std::vector<Detection>& dets,
                                        const std::vector<double>& scores,
                                        const std::vector<OrientedBox>& det_world,
                                        const Eigen::Vector3d& sensor,
                                        const Eigen::Vector4d* floor) const;
    void predict(double dt, const Eigen::Vector3d& sensor, TrackerFrameResult& out);
    void apply_motion_prior(double stamp_s,
                            double dt);  ///< objects not associated at stamp_s decay
    void merge_duplicates(TrackerFrameResult& out);
    /// An object at rest whose detections agree, twice in a row, that it was turned beyond its
    /// class's turn_release_rad gets the yaw uncertainty of a moving one for this update.
    void turn_where_it_stands(Track& t, const OrientedBox& detection_world, double dt) const;
    bool in_range(const OrientedBox& box, const Eigen::Vector3d& sensor) const;
    /// One frame's existence evidence for `t` (a detection's score, or 0 for an unexplained
    /// miss), folded into its open view or opening a new one; a miss adds to t.misses once per
    /// view, a detection ends the run of misses.
    void judge(Track& t, double evidence, bool miss, const Eigen::Vector3d& sensor,
               double stamp_s) const;

    TrackerParams params_;
    std::function<bool(const Eigen::Vector2d&)> region_;
    std::unordered_map<std::uint32_t, Track> tracks_;
    std::uint32_t next_id_ = 1;
    bool started_ = false;
    double last_stamp_s_ = 0.0;
};

}  // namespace makeway::tracking

#pragma once
// The online system (the paper's method, "ours"), one sweep at a time, fed only what a robot has:
// sweeps with per-point time, wheel odometry, the start pose, the extrinsics, and the CAD models of
// the room's furniture (the static map of walls goes to the Navigator). No simulator type can
// reach it: this library links no sim/ or eval/ code (a test checks the rule), and the sensor's
// points enter without the simulator's labels and instance ids.
//
//   sweep + wheel odometry -> LiDAR odometry (registration against a local map, the wheels as
//     prior; or the wheels alone) -> pose at sweep start and end
//   every `keyframe.every` sweeps:
//     keyframe: the last `window` sweeps de-skewed and accumulated into the newest sweep's frame
//     ground plane (RANSAC, first keyframe), ground and ceiling removed
//     detector -> verification against the CAD models (p_exist) -> object map (tracker)
//     with a shape prior: what no CAD model fits is verified against a learned shape, kept per
//     tracked object and completed again from each new view (TrackedShapes)
#include <cstddef>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <unordered_map>
#include <vector>

#include "makeway/common/detection.hpp"
#include "makeway/common/object_estimate.hpp"
#include "makeway/common/point_cloud.hpp"
#include "makeway/common/transforms.hpp"
#include "makeway/perception/object_detector.hpp"
#include "makeway/pipeline/front_end.hpp"
#include "makeway/pipeline/keyframe.hpp"
#include "makeway/pipeline/system_params.hpp"
#include "makeway/pipeline/tracked_shapes.hpp"
#include "makeway/tracking/object_map.hpp"
#include "makeway/verification/cad_library.hpp"
#include "makeway/verification/verifier.hpp"

namespace makeway::pipeline {

/// Wall-clock time of each stage [ms] (zero for stages that did not run).
struct StageTiming {
    double deskew_ms = 0.0;    ///< every sweep: its pose and de-skewing into the world
    double odometry_ms = 0.0;  ///< ... of which the LiDAR odometry's registration
    double accumulate_ms = 0.0, ground_ms = 0.0, detect_ms = 0.0, verify_ms = 0.0,
           track_ms = 0.0;  ///< keyframes
    double shape_ms = 0.0;  ///< keyframes with a shape prior: the tracked objects' shapes completed
                            ///< from their views
    double total_ms = 0.0;  ///< the whole process_sweep
    /// The keyframe chain: accumulation to the object map.
    double keyframe_ms() const {
        return accumulate_ms + ground_ms + detect_ms + verify_ms + track_ms + shape_ms;
    }
};

/// Everything one keyframe produced, for tests, evaluation and pictures (no side channels).
struct KeyframeResult {
    std::size_t index = 0;
    double stamp_s = 0.0;
    Isometry3 T_world_keyframe = Isometry3::Identity();     ///< the pipeline's estimate
    PreparedKeyframe prepared;                              ///< ground-filtered cloud and plane
    std::vector<Detection> detections;                      ///< the network's, sensor frame
    std::vector<verification::VerifiedDetection> verified;  ///< empty without a CAD library
    std::vector<Detection> evidence;                        ///< what the tracker was fed
    tracking::TrackerFrameResult tracking;
    std::size_t shapes_completed = 0;  ///< tracked objects whose shape was completed anew
};

struct SweepResult {
    Isometry3 T_world_sensor_start = Isometry3::Identity();  ///< estimated
    Isometry3 T_world_sensor_end = Isometry3::Identity();
    Pose2 pose;  ///< the base at the sweep's end, estimated
    PointCloud
        points_world;  ///< this sweep de-skewed into the world frame (the obstacle layer's input)
    std::optional<odometry::OdometryResult>
        odometry;  ///< the LiDAR odometry's report, when it runs
    std::optional<KeyframeResult> keyframe;
    bool keyframe_formed = false;  ///< the front end formed a keyframe (perceived in `keyframe`, or
                                   ///< handed on by track())
    std::vector<ObjectEstimate> objects;  ///< the object map after this sweep, world frame
    StageTiming timing;
};

/// A keyframe the front end formed, waiting for perception (Pipeline::perceive).
struct PendingKeyframe {
    FrontEndKeyframe front;
    double stamp_s = 0.0;
};

class Pipeline {
  public:
    /// `detector` and `library` may be null (no detection / no verification); both must outlive
    /// the pipeline. Throws std::invalid_argument listing every problem of `params` (and of its ICP
    /// levels against the library's).
    Pipeline(const SystemParams& params, const Pose2& start_pose,
             const perception::ObjectDetector* detector, const verification::CadLibrary* library);

    /// The whole method for one sweep, top to bottom. Never throws on degenerate input (an empty
    /// sweep gives an empty keyframe and no detections).
    /// The sweep is taken by value: a caller done with it moves it in (no copy of its points).
    SweepResult process_sweep(Sweep sweep);

    /// process_sweep() in two halves, for a robot that must not wait for perception before it
    /// acts: track() is the front end (pose, de-skewing, keyframe assembly; the object map as it
    /// stands), and hands a keyframe it formed to `pending`; perceive() is the keyframe chain
    /// (detect, verify, track) and updates the object map. They share no state but the object
    /// map (guarded), so perceive() may run on another thread than track(), one call at a time.
    /// process_sweep(s) == track(s, &p) then perceive(p).
    SweepResult track(Sweep sweep, std::optional<PendingKeyframe>* pending);
    KeyframeResult perceive(PendingKeyframe pending, StageTiming& timing);
    /// The object map now (a copy: perceive() may be updating it).
    std::vector<ObjectEstimate> objects() const;

    /// Where objects can stand: the free space of the prebuilt map of walls (a robot has it).
    /// Objects outside it (beyond the walls, inside them) never enter the object map.
    void set_object_region(std::function<bool(const Eigen::Vector2d&)> allowed) {
        map_.set_region(std::move(allowed));
    }
    /// A learned shape prior (may be null; must outlive the pipeline): detections no CAD model
    /// fits, or all detections when there is no library, are verified against its completed shape,
    /// kept per tracked object and completed again from each new view (TrackedShapes).
    void set_shape_prior(const verification::ShapePrior* prior);
    /// The learned shapes of the tracked objects (null without a shape prior).
    const TrackedShapes* tracked_shapes() const { return shapes_.get(); }

    const SystemParams& params() const { return params_; }
    std::size_t keyframes() const { return keyframes_; }

  private:
    KeyframeResult process_keyframe(FrontEndKeyframe front, double stamp_s, StageTiming& timing);
    /// Per detection, the fit of the tracked object it shows (VerifyParams::reseed_*), if any.
    std::vector<std::optional<verification::VerifySeed>> seeds_for(
        const std::vector<Detection>& detections, const Isometry3& T_world_keyframe,
        double stamp_s) const;
    /// Keeps the fits of this keyframe's accepted detections under their tracks; forgets dead
    /// tracks'.
    void remember_fits(const KeyframeResult& kf);
    /// Gives each object with a CAD fit the outlines of that model's body-height parts, at the
    /// fit moved with the object's box since (ObjectEstimate::parts_world).
    void attach_parts(std::vector<ObjectEstimate>& objects);

    struct TrackFit {  ///< a tracked object's last CAD fit
        const verification::CadModel* model = nullptr;
        Isometry3 T_world_object = Isometry3::Identity();
        double residual_m = 0.0, stamp_s = 0.0;
    };

    SystemParams params_;
    const perception::ObjectDetector* detector_;
    const verification::CadLibrary* library_;
    std::unique_ptr<TrackedShapes> shapes_;  ///< wraps the shape prior
    verification::CadLibrary
        no_library_;  ///< what verification sees with a prior and no CAD models
    FrontEnd front_end_;
    tracking::ObjectMap map_;
    std::unordered_map<std::uint32_t, TrackFit> fits_;  ///< by track id
    /// verification::part_outlines per model, for the collision monitor's body (computed once).
    std::unordered_map<const verification::CadModel*, std::vector<Polygon2>> part_outlines_;
    mutable std::mutex objects_mutex_;
    std::vector<ObjectEstimate> objects_;
    std::size_t keyframes_ = 0;
};

/// The tracker's parameters with misses judged only within what the detector covers. With
/// `cad_verified` evidence (the boxes of CAD models fitted to the scan), a standing object's yaw
/// keeps the filter's own random walk (MotionPrior::rest_yaw_rate_sigma_radps is for the
/// network's boxes): a fit's yaw is within a degree or off by a quarter turn, averaging gains
/// nothing there, and on `bench nav --scenes 200` it cost `ours` a fifth more avoidable risk.
tracking::TrackerParams tracker_params_for(const perception::ObjectDetector* detector,
                                           tracking::TrackerParams params, bool cad_verified);

}  // namespace makeway::pipeline

#pragma once
// The tracking benchmark: the robot drives through simulated scenes (moving chairs, people); each
// frame's detections are the ground-truth boxes of the objects the LiDAR actually sees (enough
// points in the sweep), corrupted at set rates: missed, noisy, yaw-flipped, plus false positives.
// The object map (its objects within sensor range) is scored with CLEAR MOT and HOTA against the
// objects within range that have been seen at least once: a map remembers what is out of view.
#include <functional>
#include <map>

#include "makeway/eval/map_sanity.hpp"
#include "makeway/eval/tracking_metrics.hpp"
#include "makeway/tracking/object_map.hpp"

namespace makeway::eval {

struct TrackBenchParams {
    int scenes = 5;
    std::uint64_t seed = 0;
    int max_frames = 400;                 ///< per scene (10 Hz)
    std::size_t min_visible_points = 15;  ///< an object with fewer points in the sweep is not seen
    double p_miss = 0.2;
    double false_positive_rate = 0.1;  ///< false detections per frame, per visible object
    double centre_sigma_m = 0.05;
    double size_sigma = 0.05;  ///< relative
    double yaw_sigma_deg = 3.0;
    double p_flip_90 = 0.05;  ///< each of +-pi/2
    double p_flip_180 = 0.1;
    bool use_scan_occlusion = false;  ///< also give the tracker the sweep for occlusion (default:
                                      ///< the paper's object boxes only)
    tracking::TrackerParams tracker;
};

struct TrackBenchResult {
    TrackingMetrics overall;
    std::map<ObjectClass, TrackingMetrics> per_class;
    double fps = 0.0;  ///< tracker updates per second, one core
    double mean_detections_per_frame = 0.0;
    double yaw_within_10deg_detections = 0.0;  ///< of true detections, up to the object's symmetry
    double yaw_within_10deg_map = 0.0;         ///< of map objects matched to ground truth
    std::size_t occlusion_gaps = 0;       ///< unseen stretches of up to 2 s of a tracked object
    std::size_t occlusion_gaps_kept = 0;  ///< ... after which the object kept its track id
    std::size_t false_positives = 0;
    std::size_t false_positive_tracks_output =
        0;  ///< frames in which a false positive's track was in the map
    std::size_t false_positive_tracks_lingering =
        0;  ///< false positives' tracks still there 3 frames after birth
    std::size_t frames = 0;
    MapSanity map_sanity;  ///< every map object of every frame against the truth
};

TrackBenchResult run_track_bench(const TrackBenchParams& params,
                                 const std::function<void(int, int)>& progress = {});

}  // namespace makeway::eval

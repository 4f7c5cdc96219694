#pragma once
// makeway track's options and its KITTI path (track_kitti.cpp): one object map per KITTI type and
// sequence, as AB3DMOT tracks; cmd_track.cpp holds the command, the makeway-format path and the
// summary.
#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "io/tracking_io.hpp"
#include "makeway/tracking/object_map.hpp"

namespace makeway::apps {

struct TrackOptions {
    std::string detections;  ///< folder of per-frame JSON (makeway) or KITTI file / folder of files
    std::string format = "makeway";
    std::string poses;   ///< TUM sensor poses per frame (makeway format, optional)
    std::string config;  ///< YAML; its tracking section (default: built-in, KITTI preset for kitti)
    double rate_hz = 10.0;  ///< frame rate for KITTI files (stamps = frame / rate)
    std::optional<double> range_m, min_score;
    std::vector<std::string>
        classes;  ///< empty: every class in the input (kitti), chair and table (makeway)
    std::string score_transform = "auto";  ///< auto, none or sigmoid
    std::string out_of_range;              ///< freeze or drop; empty: the configuration's
    double fov_deg = 0.0;  ///< > 0: KITTI output only within this horizontal field of view
    std::string output_score = "detection";  ///< kitti: detection, existence or track-mean
    bool coasting = false;    ///< kitti: boxes of confirmed tracks not detected in the frame, every
                              ///< type (default: the type's preset)
    int coasting_frames = 0;  ///< kitti, with coasting: at most this many frames after the last
                              ///< detection (0: until dropped)
    bool no_coasting = false;  ///< kitti: no such boxes for any type
    bool backfill = true;      ///< kitti: a confirmed track's output starts at its first detection
    std::string out;
};

struct KittiSequenceInput {
    std::filesystem::path file;
    std::vector<io::KittiTrackingRecord> records;
};

struct TrackRun {
    std::size_t frames = 0;  // frames the tracker processed
    double update_s = 0.0;   // tracker updates only: reading and writing excluded
    std::map<std::string, std::size_t> tracks_per_class;
};

// The frames after its last detection that a confirmed track's predicted box is written for, per
// KITTI type: -1 none, 0 until the track is dropped (track_kitti.cpp: the presets and why).
int coasting_frames_for(const TrackOptions& o, const std::string& type);

// One sequence, one object map per class (as AB3DMOT): every frame, also those without
// detections; each output box carries its last detection's 2D box, truncation and occlusion.
std::vector<io::KittiTrackingRecord> track_kitti_sequence(
    const KittiSequenceInput& in, const std::vector<std::string>& types,
    const std::map<std::string, tracking::TrackerParams>& params_of, const TrackOptions& o,
    TrackRun& run);

// The classes to track: the requested ones, or every type in the input but DontCare.
std::vector<std::string> kitti_types(const std::vector<KittiSequenceInput>& inputs,
                                     const TrackOptions& o);

}  // namespace makeway::apps

#pragma once
// What `makeway scene`, `makeway simulate` and `makeway demo` share: writing a scene with its
// picture, and recording a drive to a folder.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "makeway/sim/sequence.hpp"

namespace makeway::apps {

/// scene.yaml plus scene.png beside it (with the robot's auto route). Returns a one-line summary.
std::string write_scene_with_picture(const std::filesystem::path& path, const sim::Scene& scene);

/// The auto route for the scene, or throws io::FileError naming `scene_name`.
std::vector<Eigen::Vector2d> auto_route(const sim::Scene& scene, const sim::RobotParams& robot,
                                        const std::string& scene_name);

struct RecordingSummary {
    int frames = 0;
    bool reached_goal = false;
    std::size_t frames_in_collision = 0;
    double distance_m = 0.0;
    double ms_per_frame = 0.0;
    std::size_t points = 0;
};

struct RecordingOptions {
    int frames = 100;  ///< sweeps to simulate (at most, with stop_at_goal)
    std::string format =
        "pcd";  ///< "pcd" (binary, labelled), "bin" (KITTI + SemanticKITTI labels) or "bag" (ROS 1)
    int cloud_every = 1;  ///< write every n-th sweep's cloud (ground truth is written for all)
    bool stop_at_goal = false;
};

/// An upper bound on the bytes a recording writes (every ray returning).
std::uintmax_t recording_bytes_upper_bound(const sim::LidarParams& lidar,
                                           const RecordingOptions& options);

/// Records sweeps into out_dir: clouds/NNNNNN.pcd (or .bin + labels/NNNNNN.label),
/// objects/NNNNNN.json, poses_gt.txt, odometry.txt, scene.png, summary.json. Shows progress.
/// Checks the free disk space first (FileError). Written in place with a PARTIAL marker
/// (io::RecordingFolder): a failure or Ctrl-C leaves the marker and summary.json with
/// "complete": false and the frames that are on disk, then rethrows.
RecordingSummary record_sequence(const sim::Scene& scene, const std::vector<Eigen::Vector2d>& route,
                                 const sim::SequenceParams& params, const RecordingOptions& options,
                                 const std::filesystem::path& out_dir,
                                 const std::string& scene_label);

}  // namespace makeway::apps

#pragma once
// Detections and tracks on disk.
// - KITTI tracking text (one file per sequence, one object per line, camera coordinates):
//   `frame [track_id] type truncated occluded alpha x1 y1 x2 y2 h w l x y z rotation_y [score]`.
//   Lines without a track id are detections (the form AB3DMOT-style trackers read). Makeway's
//   frame is mapped to KITTI's camera frame without calibration: x_cam = -y, y_cam = -z, z_cam = x,
//   location = bottom centre, rotation_y = -yaw - pi/2 (the KITTI Velodyne-to-camera convention).
// - makeway JSON, one file per frame: detections {"stamp_s", "T_world_sensor": {"t_m", "yaw_rad"},
//   "detections": [{"class", "box", "score", "class_probabilities"}]}; objects (tracks and ground
//   truth, as `makeway simulate` writes them) {"frame", "stamp_s", "objects": [{"id", "class",
//   "box_world", ...}]}.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/json_io.hpp"
#include "makeway/common/detection.hpp"
#include "makeway/common/object_estimate.hpp"
#include "makeway/common/transforms.hpp"

namespace makeway::io {

struct KittiTrackingRecord {
    int frame = 0;
    int track_id = -1;  ///< -1: a detection
    std::string type;   ///< "Chair", "Table", or any KITTI type (kept, not tracked)
    double truncated = 0.0, occluded = 0.0, alpha = 0.0;
    std::array<double, 4> bbox_px{0, 0, 0, 0};  ///< 2D box, unused here
    double h_m = 0.0, w_m = 0.0, l_m = 0.0;
    Eigen::Vector3d location_cam_m = Eigen::Vector3d::Zero();  ///< bottom centre
    double rotation_y_rad = 0.0;
    std::optional<double> score;
    bool is_dont_care() const;  ///< a DontCare region (2D box only): ignored by evaluations
};

/// KITTI tracking text (labels, or results with a score), or AB3DMOT's comma-separated detection
/// files (frame, type 1-3, 2D box, score, h w l, x y z, rotation_y, alpha), line by line.
std::vector<KittiTrackingRecord> parse_kitti_tracking(std::string_view text);
/// Throws FileError "PATH: line N: problem". An empty file is a sequence without objects.
std::vector<KittiTrackingRecord> read_kitti_tracking(const std::filesystem::path& path);
void write_kitti_tracking(const std::filesystem::path& path,
                          const std::vector<KittiTrackingRecord>& records);

/// chair/table from a KITTI type name (any case), nullopt for other types.
std::optional<ObjectClass> class_of_kitti_type(std::string_view type);
/// A box as a KITTI record: camera-frame 3D fields and alpha; bbox_px -1 (no camera model here).
KittiTrackingRecord to_kitti(const OrientedBox& box, ObjectClass cls, int frame, int track_id,
                             std::optional<double> score);
KittiTrackingRecord to_kitti(const OrientedBox& box, const std::string& type, int frame,
                             int track_id, std::optional<double> score);
/// The record's box in makeway's frame convention (x forward, y left, z up).
OrientedBox box_from_kitti(const KittiTrackingRecord& r);

/// One frame of detections in makeway JSON.
struct DetectionFrame {
    double stamp_s = 0.0;
    std::optional<Isometry3> T_world_sensor;
    std::vector<Detection> detections_sensor;
};
/// Accepts {"detections": [...]} (with optional stamp_s and T_world_sensor) or a bare list.
/// Throws FileError naming the file and the detection.
/// The same from text; throws FormatError ("detection N: problem").
DetectionFrame parse_detection_frame(std::string_view text, bool any_score = false);
/// Scores must be in [0, 1] unless any_score (any finite number: raw logits, for a score
/// transform).
DetectionFrame read_detection_frame(const std::filesystem::path& path, bool any_score = false);
Json to_json(const DetectionFrame& frame);

/// Objects of one frame (tracks or ground truth). With `stamp_s`, the frame's `stamp_s` is
/// required too and written there.
std::vector<ObjectEstimate> read_object_frame(const std::filesystem::path& path,
                                              double* stamp_s = nullptr);
Json objects_to_json(int frame, double stamp_s, const std::vector<ObjectEstimate>& objects);

/// The frame files of a folder (*.json or *.txt), sorted by name; throws FileError when none.
std::vector<std::filesystem::path> frame_files(const std::filesystem::path& dir,
                                               const std::string& extension);
/// KITTI tracking input: one file, or every .txt of a folder (one sequence each), by name.
std::vector<std::filesystem::path> kitti_sequence_files(const std::filesystem::path& path);

}  // namespace makeway::io

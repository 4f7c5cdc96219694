#pragma once
// Top-down pictures (PNG through cairo): points coloured by label, oriented boxes, a scale bar.
#include <filesystem>
#include <string>
#include <vector>

#include "io/canvas.hpp"
#include "makeway/common/detection.hpp"
#include "makeway/common/object_estimate.hpp"
#include "makeway/common/point_cloud.hpp"

namespace makeway::io {

/// The colour each semantic label is drawn in, in every picture.
Rgb label_colour(SemanticLabel label);
/// A box's footprint with a line from its centre to its front (+x) face.
void draw_box(Canvas& canvas, const OrientedBox& box, const Rgb& colour);

struct TopDownStyle {
    double pixels_per_m = 60.0;
    double margin_m = 0.5;
    std::string title;
};

/// Draws the cloud (coloured by semantic label when it has labels, else by height) and the objects,
/// with each box's heading marked. Atomic write; throws FileError.
void write_top_down_png(const std::filesystem::path& path, const PointCloud& cloud,
                        const std::vector<ObjectEstimate>& objects, const TopDownStyle& style = {});

/// What a detector made of one cloud, from above, in the sensor frame: the points within reach_m of
/// the sensor (light grey: all of them; by height: `kept`, what the detector was given once ground
/// and ceiling were removed), each detection's box in its class colour with its class and score
/// written beside it, the sensor's position and a scale bar. For a user's own frame, where no
/// truth says what is there. Atomic write; throws FileError.
void write_detections_png(const std::filesystem::path& path, const PointCloud& raw,
                          const PointCloud& kept, const std::vector<Detection>& detections,
                          double reach_m, const std::string& title);

}  // namespace makeway::io

#pragma once
// The detector's input and output geometry: a bird's-eye-view grid around the sensor. Input cells
// hold height-sliced occupancy (PIXOR-style: log point counts per height slice, the top height and
// the mean intensity), cheap to build on a CPU and enough to see legs, seats, backs and table tops
// in colourless LiDAR. Outputs live on the same grid at a stride.
#include <string>
#include <vector>

#include "makeway/common/detection.hpp"
#include "makeway/common/point_cloud.hpp"

namespace makeway::perception {

struct BevGridParams {
    double range_m = 8.0;  ///< square [-range, range]^2 around the sensor [m]
    double cell_m = 0.1;   ///< input cell [m]
    double z_min_m =
        -0.5;  ///< height band in the sensor frame [m] (sensor ~0.45 m above the floor)
    double z_max_m = 1.3;
    int height_slices = 9;
    int output_stride = 2;  ///< output cells are stride x input cells
    /// A mean-intensity channel. Off by default: with intensity that reveals only material (see
    /// sim/world.hpp), it did not help (README, "Intensity channel"), and sensors differ in it.
    bool intensity = false;
    std::vector<std::string> validate() const;

    int cells() const {
        return static_cast<int>(2.0 * range_m / cell_m + 0.5);
    }                                                          ///< per side, input
    int out_cells() const { return cells() / output_stride; }  ///< per side, output
    int channels() const { return height_slices + 1 + (intensity ? 1 : 0); }
    double out_cell_m() const { return cell_m * output_stride; }
};

/// Channels x cells x cells, row-major (channel, iy, ix); ix along +x, iy along +y.
std::vector<float> encode_bev(const PointCloud& cloud_sensor, const BevGridParams& params);

/// The network's heads on the output grid, channel-major: class heatmaps (after sigmoid) then
/// centre offset x, y [cells], z [m], log size l, w, h [log m], sin yaw, cos yaw.
constexpr int kHeadChannels = kNumObjectClasses + 8;

struct DecodeParams {
    double score_threshold = 0.3;
    int max_candidates = 200;
    double nms_bev_iou = 0.25;
    /// Boxes outside these sizes, or with any non-finite value, are never detections: a network fed
    /// garbage (an absurd intensity, a corrupt cloud) must not report confident garbage.
    double min_size_m = 0.05;
    double max_size_m = 5.0;
};

/// Peaks (3x3 local maxima above the threshold) of the heatmaps into boxes, then rotated NMS.
/// Class probabilities: each class heatmap at the peak, normalised; score: the peak value.
std::vector<Detection> decode_heads(const std::vector<float>& heads, const BevGridParams& grid,
                                    const DecodeParams& params);

}  // namespace makeway::perception

#pragma once
// Training the shape networks from examples (what they are made of is eval/shape_dataset's job:
// the simulator's procedural furniture, rendered by its LiDAR). F_n end to end through the
// differentiable upright solve, F_0 as an auto-decoder (a code per shape), F_1 on TSDF volumes
// fused from the views of each shape, conditioned on that shape's F_0 code.
#include <functional>
#include <string>
#include <vector>

#include "makeway/shape/shape_model.hpp"

namespace makeway::shape {

/// One object shape and its targets in its canonical frame.
struct ShapeExample {
    ObjectClass cls = ObjectClass::kChair;
    std::string style;
    /// Yaw turns [rad] that map the shape onto itself (0 always first): a chair has none other, a
    /// rectangular table pi, a round one every sampled angle. F_n is taught the nearest of them.
    std::vector<double> symmetry_yaws{0.0};
    std::vector<Eigen::Vector3f> sdf_points;  ///< near-surface and uniform samples
    std::vector<float> sdf;                   ///< their signed distances (canonical units)
    std::vector<Eigen::Vector3f> occupancy_points;
    std::vector<std::uint8_t> occupied;
};

/// One partial observation of a shape, in its gravity frame.
struct ShapeView {
    int shape = 0;  ///< index into ShapeTrainingSet::shapes
    std::vector<Eigen::Vector3d> points;
    std::vector<std::uint8_t> outlier;  ///< injected depth outliers and other objects' points
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< the sensor
    Similarity3 truth;                                 ///< T_gravity_canonical
};

struct ShapeTrainingSet {
    std::vector<ShapeExample> shapes;
    std::vector<ShapeView> views;
};

struct ShapeTrainParams {
    int correspondence_steps = 4000;
    int sdf_steps = 1000;
    int occupancy_steps = 1200;
    int correspondence_batch = 16;
    int sdf_batch_shapes = 16, sdf_samples = 256;
    int occupancy_batch = 8, occupancy_samples = 512;
    int fusions_per_shape = 4;    ///< TSDF volumes fused per shape for F_1 (1-3 of its views each)
    double learning_rate = 1e-3;  ///< Adam, cosine-decayed
    std::uint64_t seed = 0;
    int threads = 0;  ///< 0: torch's default
    std::vector<std::string> validate() const;
};

struct NetLoss {
    double first = 0.0, last = 0.0;  ///< mean loss over the first and the last 5 % of the steps
};

struct ShapeTrainReport {
    NetLoss correspondence[2], sdf[2], occupancy[2];  ///< per class (chair, table)
    double seconds = 0.0;
    double stage_seconds[3] = {0.0, 0.0, 0.0};  ///< F_n, F_0, F_1 over both classes
};

/// Trains all six networks in place. `progress(stage, step, steps, loss)` after each step.
ShapeTrainReport train_shape_model(
    ShapeModel& model, const ShapeTrainingSet& data, const ShapeTrainParams& params,
    const std::function<void(const std::string&, int, int, double)>& progress = {});

/// The yaw turns among multiples of 15 deg that map surface samples onto the surface (RMS distance
/// under `tolerance`, canonical units), 0 first.
std::vector<double> detect_symmetry_yaws(
    const std::vector<Eigen::Vector3d>& surface,
    const std::function<double(const Eigen::Vector3d&)>& distance, double tolerance = 0.02);

}  // namespace makeway::shape

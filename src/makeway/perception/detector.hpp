#pragma once
// The neural 3D detector (libtorch, CPU): height-sliced BEV occupancy -> a small 2D encoder-decoder
// -> CenterNet-style heads (class heatmaps, centre offset, z, log size, sin/cos yaw) on a stride-2
// grid -> peaks -> rotated NMS. The network is in the networks' module (src/makeway/neural/, the
// only code that includes torch), opened on first use: perception/neural_module.hpp.
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "makeway/common/detection.hpp"
#include "makeway/common/point_cloud.hpp"
#include "makeway/perception/bev_grid.hpp"
#include "makeway/perception/object_detector.hpp"

namespace makeway::perception {

struct DetectorParams {
    BevGridParams grid;
    DecodeParams decode;
    int width = 32;  ///< channels of the first stage (the second has twice as many)
    /// The sensor height above the floor the network was trained at [m]: with a keyframe's ground
    /// plane, the cloud is levelled to it first (levelling.hpp), so any mounting looks like the
    /// training's. 0: the cloud is taken as the sensor gave it (models before levelling).
    double level_height_m = 0.0;
    int threads = 0;         ///< intra-op threads for inference; 0: leave torch's default
    std::uint64_t seed = 0;  ///< weight initialisation
};

class Detector : public ObjectDetector {
  public:
    /// A freshly initialised network (seeded).
    explicit Detector(const DetectorParams& params = {});
    ~Detector() override;
    Detector(Detector&&) noexcept;
    Detector& operator=(Detector&&) noexcept;

    /// Throws std::runtime_error naming the file on a missing or corrupt model.
    static Detector load(const std::filesystem::path& path);
    /// Atomic (written beside, then renamed).
    void save(const std::filesystem::path& path) const;

    /// Detections in the cloud's (sensor) frame; the cloud should be ground- and ceiling-filtered.
    /// With the keyframe's ground plane and a model trained levelled, the network sees the cloud
    /// from a level sensor at level_height_m. Safe to call from several threads at once.
    std::vector<Detection> detect(
        const PointCloud& cloud_sensor,
        const std::optional<Eigen::Vector4d>& ground_plane_sensor) const override;
    using ObjectDetector::detect;
    double reach_m() const override { return params_.grid.range_m; }
    bool uses_intensity() const override { return params_.grid.intensity; }
    /// The decoded head maps for a cloud (channel-major, see bev_grid.hpp).
    std::vector<float> heads(const PointCloud& cloud_sensor) const;

    const DetectorParams& params() const { return params_; }
    std::size_t parameter_count() const;

    struct Impl;  ///< the network (detector_backend.hpp), in the networks' module
    Impl& impl() const { return *impl_; }

  private:
    Detector(const DetectorParams& params, std::unique_ptr<Impl> impl);
    DetectorParams params_;
    std::unique_ptr<Impl> impl_;
};

/// Threads torch, and the OpenBLAS under it when that is the BLAS linked, use for inference and
/// training in this process: applied when the networks' module opens, and at once when it is open
/// (setting them does not open it).
void set_inference_threads(int threads);

/// A labelled training sample: a keyframe and its boxes in the sensor frame, and the keyframe's
/// ground plane (levelled to the detector's level_height_m when both are there).
struct TrainingSample {
    const PointCloud* cloud_sensor = nullptr;
    std::vector<std::pair<ObjectClass, OrientedBox>> boxes;
    std::optional<Eigen::Vector4d> ground_plane_sensor;
};

struct TrainParams {
    int epochs = 20;
    int batch_size = 8;
    double learning_rate = 2e-3;  ///< AdamW peak, cosine-decayed after a 5 % warm-up
    double weight_decay = 1e-4;
    std::uint64_t seed = 0;
    bool augment = true;  ///< rotation about z, flip, subsampling, range dropout
    int threads = 0;      ///< 0: torch's default
    std::filesystem::path
        checkpoint;  ///< written every epoch when set; resumed from when it exists
    std::vector<std::string> validate() const;
};

struct EpochReport {
    int epoch = 0;
    double mean_loss = 0.0, heatmap_loss = 0.0, box_loss = 0.0;
};

/// Trains in place. `progress(step, steps, loss)` after each batch; `on_epoch` after each epoch.
std::vector<EpochReport> train_detector(
    Detector& detector, const std::vector<TrainingSample>& samples, const TrainParams& params,
    const std::function<void(int, int, double)>& progress = {},
    const std::function<void(const EpochReport&)>& on_epoch = {});

}  // namespace makeway::perception

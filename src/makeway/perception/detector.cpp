// The detector's facade: what does not need torch (levelling, the BEV encoding, decoding, NMS)
// runs here; the network is the module's (detector_backend.hpp).
#include "makeway/perception/detector.hpp"

#include <stdexcept>

#include "makeway/perception/detector_backend.hpp"
#include "makeway/perception/levelling.hpp"
#include "makeway/perception/model_archive.hpp"
#include "makeway/perception/neural_module.hpp"

namespace makeway::perception {

const DetectorBackend& detector_backend() {
    static const DetectorBackend& backend = neural_module_table<DetectorBackend>(
        "makeway_detector_backend", kDetectorBackendAbi, "detector");
    return backend;
}

Detector::Detector(const DetectorParams& params)
    : params_(params), impl_(detector_backend().create(params)) {}

Detector::Detector(const DetectorParams& params, std::unique_ptr<Impl> impl)
    : params_(params), impl_(std::move(impl)) {}

Detector::~Detector() = default;
Detector::Detector(Detector&&) noexcept = default;
Detector& Detector::operator=(Detector&&) noexcept = default;

std::size_t Detector::parameter_count() const { return impl_->parameter_count(); }

void Detector::save(const std::filesystem::path& path) const { impl_->save(path, params_); }

Detector Detector::load(const std::filesystem::path& path) {
    const std::string bytes = read_checked_model_archive(path, "model");
    DetectorParams params;
    std::unique_ptr<Impl> impl = detector_backend().load(bytes, path, params);
    return Detector(params, std::move(impl));
}

std::vector<float> Detector::heads(const PointCloud& cloud) const {
    return impl_->heads(encode_bev(cloud, params_.grid), params_);
}

std::vector<Detection> Detector::detect(
    const PointCloud& cloud, const std::optional<Eigen::Vector4d>& ground_plane_sensor) const {
    const std::optional<Isometry3> T_level_sensor =
        level_frame_if(ground_plane_sensor, params_.level_height_m);
    if (!T_level_sensor) return decode_heads(heads(cloud), params_.grid, params_.decode);
    std::vector<Detection> found =
        decode_heads(heads(cloud.transformed(*T_level_sensor)), params_.grid, params_.decode);
    const Isometry3 T_sensor_level = T_level_sensor->inverse();
    for (Detection& d : found) d.box_sensor = d.box_sensor.transformed(T_sensor_level);
    return found;
}

std::vector<std::string> TrainParams::validate() const {
    std::vector<std::string> p;
    if (epochs < 1 || epochs > 10000) p.push_back("epochs must be in [1, 10000]");
    if (batch_size < 1 || batch_size > 512) p.push_back("batch_size must be in [1, 512]");
    if (!(learning_rate > 0.0 && learning_rate < 1.0))
        p.push_back("learning_rate must be in (0, 1)");
    if (!(weight_decay >= 0.0 && weight_decay < 1.0)) p.push_back("weight_decay must be in [0, 1)");
    return p;
}

std::vector<EpochReport> train_detector(Detector& detector,
                                        const std::vector<TrainingSample>& samples,
                                        const TrainParams& params,
                                        const std::function<void(int, int, double)>& progress,
                                        const std::function<void(const EpochReport&)>& on_epoch) {
    if (samples.empty()) return {};
    if (params.threads > 0) set_inference_threads(params.threads);  // torch's and OpenBLAS's
    return detector_backend().train(detector.impl(), detector.params(), samples, params, progress,
                                    on_epoch);
}

}  // namespace makeway::perception

// Training the shape networks: the parameters' checks and the symmetries here, the training in
// the module (neural/shape_training.cpp, shape_backend.hpp).
#include "makeway/shape/shape_training.hpp"

#include <cmath>

#include "makeway/shape/shape_backend.hpp"

namespace makeway::shape {

std::vector<std::string> ShapeTrainParams::validate() const {
    std::vector<std::string> p;
    for (const int s : {correspondence_steps, sdf_steps, occupancy_steps}) {
        if (s < 0 || s > 1000000) p.push_back("steps must be in [0, 1000000]");
    }
    if (correspondence_batch < 1 || sdf_batch_shapes < 1 || sdf_samples < 1 ||
        occupancy_batch < 1 || occupancy_samples < 1) {
        p.push_back("batch sizes must be at least 1");
    }
    if (fusions_per_shape < 1 || fusions_per_shape > 64)
        p.push_back("fusions_per_shape must be in [1, 64]");
    if (!(learning_rate > 0.0 && learning_rate < 1.0))
        p.push_back("learning_rate must be in (0, 1)");
    return p;
}

std::vector<double> detect_symmetry_yaws(
    const std::vector<Eigen::Vector3d>& surface,
    const std::function<double(const Eigen::Vector3d&)>& distance, double tolerance) {
    std::vector<double> out{0.0};
    if (surface.empty()) return out;
    for (int k = 1; k < 24; ++k) {
        const double a = k * M_PI / 12.0;
        const Eigen::Matrix3d R = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix();
        double sum = 0.0;
        for (const auto& p : surface) sum += std::pow(distance(R * p), 2);
        if (std::sqrt(sum / static_cast<double>(surface.size())) < tolerance) out.push_back(a);
    }
    return out;
}

ShapeTrainReport train_shape_model(
    ShapeModel& model, const ShapeTrainingSet& data, const ShapeTrainParams& params,
    const std::function<void(const std::string&, int, int, double)>& progress) {
    if (params.threads > 0) set_threads(params.threads);
    return shape_backend().train(model.impl(), model.params(), data, params, progress);
}

}  // namespace makeway::shape

#pragma once
// What the networks' module exports through its tables (module.cpp), declared without torch: the
// module's exports compile in seconds instead of parsing torch's headers again.
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "makeway/perception/detector_backend.hpp"
#include "makeway/shape/shape_backend.hpp"

namespace makeway::perception {

std::unique_ptr<Detector::Impl> create_torch_detector(const DetectorParams& params);
std::unique_ptr<Detector::Impl> load_torch_detector(const std::string& bytes,
                                                    const std::filesystem::path& path,
                                                    DetectorParams& params);
std::vector<EpochReport> train_torch_detector(
    Detector::Impl& network, const DetectorParams& detector,
    const std::vector<TrainingSample>& samples, const TrainParams& params,
    const std::function<void(int, int, double)>& progress,
    const std::function<void(const EpochReport&)>& on_epoch);

/// torch's intra-op threads and OpenBLAS's (perception::set_inference_threads in the program).
void set_torch_threads(int threads);

}  // namespace makeway::perception

namespace makeway::shape {

std::unique_ptr<ShapeModel::Impl> create_torch_shape_model(const ShapeModelParams& params);
std::unique_ptr<ShapeModel::Impl> load_torch_shape_model(const std::string& bytes,
                                                         const std::filesystem::path& path,
                                                         ShapeModelParams& params);
ShapeTrainReport train_torch_shape_model(
    ShapeModel::Impl& networks, const ShapeModelParams& model, const ShapeTrainingSet& data,
    const ShapeTrainParams& params,
    const std::function<void(const std::string&, int, int, double)>& progress);

}  // namespace makeway::shape

#pragma once
// What ShapeModel asks of its networks: the contract between the program's facade
// (shape_model.cpp) and the module that holds F_n, F_0 and F_1 in libtorch (neural/shape_nets.cpp;
// perception/neural_module.hpp says why they live apart). Only plain C++ types cross it.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "makeway/shape/shape_training.hpp"

namespace makeway::shape {

/// The six networks behind a ShapeModel (`cls` is a class with networks: shape_class_index >= 0).
/// Const methods are safe from several threads at once.
struct ShapeModel::Impl {
    virtual ~Impl() = default;
    virtual std::size_t parameter_count() const = 0;
    /// The parameters and the weights, atomically (written beside, then renamed).
    virtual void save(const std::filesystem::path& path, const ShapeModelParams& params) const = 0;
    /// F_n on params.points points of the gravity frame (the facade has sampled them).
    virtual std::vector<float> correspond(ObjectClass cls,
                                          const std::vector<Eigen::Vector3d>& sample) const = 0;
    virtual std::vector<float> sdf(ObjectClass cls, const Latent& z,
                                   const std::vector<Eigen::Vector3d>& points) const = 0;
    virtual Latent fit_latent(ObjectClass cls, const std::vector<Eigen::Vector3d>& surface,
                              const std::vector<Eigen::Vector3d>& free, int iterations,
                              const ShapeModelParams& params) const = 0;
    virtual std::vector<float> occupancy(ObjectClass cls, const TsdfVolume& tsdf, const Latent& z,
                                         const std::vector<Eigen::Vector3d>& points,
                                         const ShapeModelParams& params) const = 0;
};

/// Bumped whenever ShapeModel::Impl or this table changes.
inline constexpr std::uint32_t kShapeBackendAbi = 1;

struct ShapeBackend {
    std::uint32_t abi = kShapeBackendAbi;
    std::uint32_t size = sizeof(ShapeBackend);
    /// Freshly initialised networks (seeded with params.seed).
    std::unique_ptr<ShapeModel::Impl> (*create)(const ShapeModelParams& params) = nullptr;
    /// A model file's bytes (passed model_archive_problem) -> its parameters and networks; throws
    /// std::runtime_error naming `path`.
    std::unique_ptr<ShapeModel::Impl> (*load)(const std::string& bytes,
                                              const std::filesystem::path& path,
                                              ShapeModelParams& params) = nullptr;
    /// train_shape_model's training of a ShapeModel's networks, made with `model` (the facade has
    /// set the threads). The module never sees the facade itself.
    ShapeTrainReport (*train)(
        ShapeModel::Impl& networks, const ShapeModelParams& model, const ShapeTrainingSet& data,
        const ShapeTrainParams& params,
        const std::function<void(const std::string&, int, int, double)>& progress) = nullptr;
};

/// The module's table, the module opened on first use; throws std::runtime_error when it cannot
/// be opened or was built against another interface.
const ShapeBackend& shape_backend();

}  // namespace makeway::shape

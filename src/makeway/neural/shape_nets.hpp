#pragma once
// The shape networks in libtorch (the module's; shape/shape_backend.hpp is the contract). Shared
// by shape_nets.cpp and shape_training.cpp, and the tests of the differentiable solve.
#include <torch/torch.h>

#include "makeway/neural/networks.hpp"

namespace makeway::shape {

/// F_n: [B, N, 3] points -> [B, N, 4] (canonical xyz, confidence logit).
struct CorrespondenceNetImpl : torch::nn::Module {
    explicit CorrespondenceNetImpl(int width);
    torch::Tensor forward(const torch::Tensor& points);
    torch::nn::Linear p1{nullptr}, p2{nullptr}, p3{nullptr}, h1{nullptr}, h2{nullptr}, h3{nullptr};
};
TORCH_MODULE(CorrespondenceNet);

/// F_0: [M, L + 3] (code, point) -> [M, 1] signed distance.
struct SdfDecoderImpl : torch::nn::Module {
    explicit SdfDecoderImpl(int width);
    torch::Tensor forward(const torch::Tensor& code_and_point);
    torch::nn::ModuleList layers{nullptr};
};
TORCH_MODULE(SdfDecoder);

/// F_1: volumes [B, 2, R, R, R] (TSDF, weight / (weight + 1)), codes [B, L], points [B, M, 3]
/// (canonical, divided by the grid's half extent) -> [B, M] occupancy logits.
struct OccupancyNetImpl : torch::nn::Module {
    explicit OccupancyNetImpl(int width);
    torch::Tensor encode(
        const torch::Tensor& volumes);  ///< [B, 33, R/2, R/2, R/2]: 32 TSDF features + confidence
    torch::Tensor decode(const torch::Tensor& features, const torch::Tensor& codes,
                         const torch::Tensor& points);
    torch::nn::Conv3d e1{nullptr}, e2{nullptr}, e3{nullptr};
    torch::nn::Linear fc_in{nullptr}, fc_out{nullptr};
    torch::nn::ModuleList blocks{nullptr};  ///< 3 ResNet blocks, two layers each
};
TORCH_MODULE(OccupancyNet);

struct ClassNets {
    CorrespondenceNet fn{nullptr};
    SdfDecoder f0{nullptr};
    OccupancyNet f1{nullptr};
    torch::Tensor mean_code;  ///< [L]: F_0's mean training code, where test-time fitting starts
};

struct TorchShapeModel final : ShapeModel::Impl {
    explicit TorchShapeModel(const ShapeModelParams& params);
    std::size_t parameter_count() const override;
    void save(const std::filesystem::path& path, const ShapeModelParams& params) const override;
    std::vector<float> correspond(ObjectClass cls,
                                  const std::vector<Eigen::Vector3d>& sample) const override;
    std::vector<float> sdf(ObjectClass cls, const Latent& z,
                           const std::vector<Eigen::Vector3d>& points) const override;
    Latent fit_latent(ObjectClass cls, const std::vector<Eigen::Vector3d>& surface,
                      const std::vector<Eigen::Vector3d>& free, int iterations,
                      const ShapeModelParams& params) const override;
    std::vector<float> occupancy(ObjectClass cls, const TsdfVolume& tsdf, const Latent& z,
                                 const std::vector<Eigen::Vector3d>& points,
                                 const ShapeModelParams& params) const override;
    /// The networks of a class with networks (throws std::invalid_argument for another).
    ClassNets& of(ObjectClass cls) const;
    mutable std::array<ClassNets, 2> nets;  ///< chair, table (torch's modules are handles)
};

/// A ShapeModel's networks (every ShapeModel's Impl is the module's TorchShapeModel).
inline std::array<ClassNets, 2>& torch_nets(ShapeModel::Impl& networks) {
    return static_cast<TorchShapeModel&>(networks).nets;
}

/// The weighted upright Umeyama solve, batched and differentiable: v, p [B, N, 3], w [B, N] ->
/// scale [B], rotation [B, 3, 3], translation [B, 3].
struct TorchSimilarity {
    torch::Tensor scale, rotation, translation;
    torch::Tensor apply(const torch::Tensor& v) const;  ///< [B, N, 3]
};
TorchSimilarity solve_upright_similarity(const torch::Tensor& v, const torch::Tensor& p,
                                         const torch::Tensor& w);

/// [B, 2, R, R, R] from TSDF volumes.
torch::Tensor volume_tensor(const std::vector<const TsdfVolume*>& volumes);
torch::Tensor points_tensor(const std::vector<Eigen::Vector3d>& points);  ///< [N, 3]

}  // namespace makeway::shape

#pragma once
// The detector's network in libtorch (the module's; perception/detector_backend.hpp is the
// contract). Shared by detector_net.cpp and detector_training.cpp only.
#include <torch/torch.h>

#include "makeway/neural/networks.hpp"

namespace makeway::perception {

struct ConvBnImpl : torch::nn::Module {
    ConvBnImpl(int in, int out, int stride);
    torch::Tensor forward(const torch::Tensor& x);
    torch::nn::Conv2d conv{nullptr};
    torch::nn::BatchNorm2d bn{nullptr};
};
TORCH_MODULE(ConvBn);

/// Encoder-decoder on the BEV grid: stride 2 (width), stride 4 (2 width), back to stride 2.
struct CenterNetImpl : torch::nn::Module {
    CenterNetImpl(int in_channels, int width);
    torch::Tensor forward(const torch::Tensor& bev);  ///< raw heads: heatmap logits first
    ConvBn stem{nullptr}, s2a{nullptr}, s2b{nullptr}, down{nullptr}, s4a{nullptr}, s4b{nullptr},
        head_conv{nullptr};
    torch::nn::ConvTranspose2d up{nullptr};
    torch::nn::Conv2d head{nullptr};
};
TORCH_MODULE(CenterNet);

struct TorchDetector final : Detector::Impl {
    explicit TorchDetector(const DetectorParams& params);
    std::vector<float> heads(const std::vector<float>& bev,
                             const DetectorParams& params) const override;
    std::size_t parameter_count() const override;
    void save(const std::filesystem::path& path, const DetectorParams& params) const override;
    /// torch's forward() is not const; heads() writes nothing (eval mode, no gradients).
    mutable CenterNet net{nullptr};
};

/// A Detector's network (every Detector's Impl is the module's TorchDetector).
inline CenterNet& torch_net(Detector::Impl& network) {
    return static_cast<TorchDetector&>(network).net;
}

/// Heads with the heatmaps passed through a sigmoid.
torch::Tensor activate_heads(const torch::Tensor& raw);
torch::Tensor bev_tensor(const PointCloud& cloud, const BevGridParams& grid);

}  // namespace makeway::perception

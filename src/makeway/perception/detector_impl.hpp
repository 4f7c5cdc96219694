#pragma once
// Torch internals shared by detector.cpp and detector_training.cpp only.
#include <torch/torch.h>

#include "makeway/perception/detector.hpp"

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

struct Detector::Impl {
    CenterNet net{nullptr};
};

/// Heads with the heatmaps passed through a sigmoid.
torch::Tensor activate_heads(const torch::Tensor& raw);
torch::Tensor bev_tensor(const PointCloud& cloud, const BevGridParams& grid);

}  // namespace makeway::perception

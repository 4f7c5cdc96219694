// The detector's network, its model files and its threads (the module's side of
// perception/detector_backend.hpp).
#include "makeway/neural/detector_net.hpp"

#include <dlfcn.h>

#include <stdexcept>

#include "makeway/neural/archive_file.hpp"

namespace makeway::perception {

ConvBnImpl::ConvBnImpl(int in, int out, int stride) {
    conv = register_module(
        "conv", torch::nn::Conv2d(
                    torch::nn::Conv2dOptions(in, out, 3).stride(stride).padding(1).bias(false)));
    bn = register_module("bn", torch::nn::BatchNorm2d(out));
}

torch::Tensor ConvBnImpl::forward(const torch::Tensor& x) {
    return torch::relu(bn->forward(conv->forward(x)));
}

CenterNetImpl::CenterNetImpl(int in, int w) {
    stem = register_module("stem", ConvBn(in, w, 2));
    s2a = register_module("s2a", ConvBn(w, w, 1));
    s2b = register_module("s2b", ConvBn(w, w, 1));
    down = register_module("down", ConvBn(w, 2 * w, 2));
    s4a = register_module("s4a", ConvBn(2 * w, 2 * w, 1));
    s4b = register_module("s4b", ConvBn(2 * w, 2 * w, 1));
    up = register_module(
        "up", torch::nn::ConvTranspose2d(torch::nn::ConvTranspose2dOptions(2 * w, w, 2).stride(2)));
    head_conv = register_module("head_conv", ConvBn(w, w, 1));
    head =
        register_module("head", torch::nn::Conv2d(torch::nn::Conv2dOptions(w, kHeadChannels, 1)));
    // Heatmap logits start at p = 0.1 (CenterNet), the rest near zero.
    torch::NoGradGuard no_grad;
    head->bias.zero_();
    head->bias.slice(0, 0, kNumObjectClasses).fill_(-2.19);
}

torch::Tensor CenterNetImpl::forward(const torch::Tensor& bev) {
    const torch::Tensor a = s2b->forward(s2a->forward(stem->forward(bev)));
    const torch::Tensor b = s4b->forward(s4a->forward(down->forward(a)));
    const torch::Tensor c = torch::relu(up->forward(b)) + a;  // skip connection at stride 2
    return head->forward(head_conv->forward(c));
}

torch::Tensor activate_heads(const torch::Tensor& raw) {
    return torch::cat(
        {torch::sigmoid(raw.slice(1, 0, kNumObjectClasses)), raw.slice(1, kNumObjectClasses)}, 1);
}

torch::Tensor bev_tensor(const PointCloud& cloud, const BevGridParams& g) {
    std::vector<float> bev = encode_bev(cloud, g);
    return torch::from_blob(bev.data(), {1, g.channels(), g.cells(), g.cells()}, torch::kFloat32)
        .clone();
}

TorchDetector::TorchDetector(const DetectorParams& params) {
    torch::manual_seed(params.seed);
    net = CenterNet(params.grid.channels(), params.width);
    net->eval();
}

std::unique_ptr<Detector::Impl> create_torch_detector(const DetectorParams& params) {
    return std::make_unique<TorchDetector>(params);
}

std::size_t TorchDetector::parameter_count() const {
    std::size_t n = 0;
    for (const auto& p : net->parameters()) n += static_cast<std::size_t>(p.numel());
    return n;
}

namespace {

// Grid and network shape, stored in the model file beside the weights.
torch::Tensor params_tensor(const DetectorParams& p) {
    return torch::tensor(
        {p.grid.range_m, p.grid.cell_m, p.grid.z_min_m, p.grid.z_max_m,
         static_cast<double>(p.grid.height_slices), static_cast<double>(p.grid.output_stride),
         static_cast<double>(p.width), p.decode.score_threshold, p.decode.nms_bev_iou,
         p.grid.intensity ? 1.0 : 0.0, p.level_height_m},
        torch::kFloat64);
}

}  // namespace

void TorchDetector::save(const std::filesystem::path& path, const DetectorParams& params) const {
    torch::serialize::OutputArchive archive;
    archive.write("makeway_detector_params", params_tensor(params));
    net->save(archive);
    save_archive_atomically(archive, path);
}

std::unique_ptr<Detector::Impl> load_torch_detector(const std::string& bytes,
                                                    const std::filesystem::path& path,
                                                    DetectorParams& params) {
    try {
        torch::serialize::InputArchive archive;
        archive.load_from(bytes.data(), bytes.size());
        torch::Tensor t;
        if (!archive.try_read("makeway_detector_params", t) || t.numel() < 9 || t.numel() > 11) {
            throw std::runtime_error("not a makeway detector (no parameters)");
        }
        const auto v = t.to(torch::kFloat64).contiguous();
        const double* d = v.data_ptr<double>();
        DetectorParams p;
        p.grid = {.range_m = d[0],
                  .cell_m = d[1],
                  .z_min_m = d[2],
                  .z_max_m = d[3],
                  .height_slices = static_cast<int>(d[4]),
                  .output_stride = static_cast<int>(d[5])};
        p.width = static_cast<int>(d[6]);
        p.decode.score_threshold = d[7];
        p.decode.nms_bev_iou = d[8];
        p.grid.intensity = t.numel() == 9 || d[9] != 0.0;  // files before the flag had the channel
        p.level_height_m = t.numel() == 11 ? d[10] : 0.0;  // files before levelling: none
        if (!p.grid.validate().empty() || p.width < 1 || p.width > 512 ||
            !(p.level_height_m >= 0.0 && p.level_height_m < 10.0))
            throw std::runtime_error("impossible parameters in the file");
        auto det = std::make_unique<TorchDetector>(p);
        det->net->load(archive);
        det->net->eval();
        params = p;
        return det;
    } catch (...) {
        rethrow_load_error(path, "model");
    }
}

void set_torch_threads(int threads) {
    if (threads <= 0) return;
    torch::set_num_threads(threads);
    // Debian's libtorch multiplies through the system BLAS (OpenBLAS), whose own pool of a thread
    // per core spins in sched_yield between calls: left alone, it takes the cores the caller kept
    // for other work (a quarter of the CPU samples of a study-space run; in bench nav's shards
    // four times their system time). Looked up at run time, so that any other BLAS links as well.
    using SetThreads = void (*)(int);
    if (auto* set_blas =
            reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads")))
        set_blas(threads);
}

std::vector<float> TorchDetector::heads(const std::vector<float>& bev,
                                        const DetectorParams& params) const {
    torch::NoGradGuard no_grad;
    if (params.threads > 0) torch::set_num_threads(params.threads);
    const BevGridParams& g = params.grid;
    const auto cells = static_cast<std::size_t>(g.cells());
    if (bev.size() != static_cast<std::size_t>(g.channels()) * cells * cells)
        throw std::invalid_argument("a BEV grid of another size than the detector's");
    // from_blob does not write: the network reads the caller's grid in place.
    const torch::Tensor in = torch::from_blob(
        const_cast<float*>(bev.data()), {1, g.channels(), g.cells(), g.cells()}, torch::kFloat32);
    // The network is in eval mode since construction, load() or the end of training: nothing here
    // writes to it, so several threads may detect at once.
    const torch::Tensor out = activate_heads(net->forward(in)).contiguous();
    return std::vector<float>(out.data_ptr<float>(), out.data_ptr<float>() + out.numel());
}

}  // namespace makeway::perception

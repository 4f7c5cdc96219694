// The shape networks' modules, inference and model files (the module's side of
// shape/shape_backend.hpp).
#include "makeway/neural/shape_nets.hpp"

#include <cmath>
#include <stdexcept>

#include "makeway/neural/archive_file.hpp"

namespace makeway::shape {

namespace F = torch::nn::functional;

CorrespondenceNetImpl::CorrespondenceNetImpl(int w) {
    p1 = register_module("p1", torch::nn::Linear(3, w));
    p2 = register_module("p2", torch::nn::Linear(w, 2 * w));
    p3 = register_module("p3", torch::nn::Linear(2 * w, 4 * w));
    h1 = register_module("h1", torch::nn::Linear(w + 2 * w + 4 * w, 4 * w));
    h2 = register_module("h2", torch::nn::Linear(4 * w, 2 * w));
    h3 = register_module("h3", torch::nn::Linear(2 * w, 4));
}

torch::Tensor CorrespondenceNetImpl::forward(const torch::Tensor& x) {
    const torch::Tensor f1 = torch::relu(p1(x));
    const torch::Tensor f2 = torch::relu(p2(f1));
    const torch::Tensor f3 = p3(f2);
    const torch::Tensor global = std::get<0>(f3.max(1, true)).expand({-1, x.size(1), -1});
    const torch::Tensor h = torch::relu(h1(torch::cat({f1, f2, global}, 2)));
    return h3(torch::relu(h2(h)));
}

SdfDecoderImpl::SdfDecoderImpl(int w) {
    layers = register_module("layers", torch::nn::ModuleList());
    const int in = kLatentDim + 3;
    // Eight layers; the fourth's output leaves room for the input, concatenated again (the skip).
    layers->push_back(torch::nn::Linear(in, w));
    layers->push_back(torch::nn::Linear(w, w));
    layers->push_back(torch::nn::Linear(w, w));
    layers->push_back(torch::nn::Linear(w, w - in));
    layers->push_back(torch::nn::Linear(w, w));
    layers->push_back(torch::nn::Linear(w, w));
    layers->push_back(torch::nn::Linear(w, w));
    layers->push_back(torch::nn::Linear(w, 1));
}

torch::Tensor SdfDecoderImpl::forward(const torch::Tensor& input) {
    torch::Tensor h = input;
    const auto softplus = F::SoftplusFuncOptions().beta(100);
    for (std::size_t i = 0; i < layers->size(); ++i) {
        if (i == 4) h = torch::cat({h, input}, 1);
        h = layers[i]->as<torch::nn::Linear>()->forward(h);
        if (i + 1 < layers->size()) h = F::softplus(h, softplus);
    }
    return torch::tanh(h);
}

OccupancyNetImpl::OccupancyNetImpl(int w) {
    e1 = register_module("e1", torch::nn::Conv3d(torch::nn::Conv3dOptions(2, 16, 3).padding(1)));
    e2 = register_module(
        "e2", torch::nn::Conv3d(torch::nn::Conv3dOptions(16, 32, 3).padding(1).stride(2)));
    e3 = register_module("e3", torch::nn::Conv3d(torch::nn::Conv3dOptions(32, 32, 3).padding(1)));
    fc_in = register_module("fc_in", torch::nn::Linear(32 + 1 + kLatentDim + 3, w));
    blocks = register_module("blocks", torch::nn::ModuleList());
    for (int i = 0; i < 6; ++i) blocks->push_back(torch::nn::Linear(w, w));
    fc_out = register_module("fc_out", torch::nn::Linear(w, 1));
}

torch::Tensor OccupancyNetImpl::encode(const torch::Tensor& volumes) {
    const torch::Tensor f = e3(torch::relu(e2(torch::relu(e1(volumes)))));
    // The confidence channel is the weight volume itself, pooled to the feature grid.
    const torch::Tensor c = F::avg_pool3d(volumes.slice(1, 1, 2), F::AvgPool3dFuncOptions(2));
    return torch::cat({f, c}, 1);
}

torch::Tensor OccupancyNetImpl::decode(const torch::Tensor& features, const torch::Tensor& codes,
                                       const torch::Tensor& points) {
    const auto b = points.size(0), m = points.size(1);
    // grid_sample wants (x, y, z) in [-1, 1] against a [B, C, D=z, H=y, W=x] volume.
    const torch::Tensor grid = points.view({b, 1, 1, m, 3});
    const torch::Tensor sampled =
        F::grid_sample(features, grid,
                       F::GridSampleFuncOptions().align_corners(false).padding_mode(torch::kBorder))
            .view({b, features.size(1), m})
            .transpose(1, 2);
    const torch::Tensor z = codes.unsqueeze(1).expand({-1, m, -1});
    torch::Tensor h = fc_in(torch::cat({sampled, z, points}, 2));
    for (std::size_t i = 0; i < blocks->size(); i += 2) {
        const torch::Tensor r = blocks[i + 1]->as<torch::nn::Linear>()->forward(
            torch::relu(blocks[i]->as<torch::nn::Linear>()->forward(torch::relu(h))));
        h = h + r;
    }
    return fc_out(torch::relu(h)).squeeze(2);
}

torch::Tensor TorchSimilarity::apply(const torch::Tensor& v) const {
    return scale.view({-1, 1, 1}) * torch::matmul(v, rotation.transpose(1, 2)) +
           translation.unsqueeze(1);
}

TorchSimilarity solve_upright_similarity(const torch::Tensor& v, const torch::Tensor& p,
                                         const torch::Tensor& w) {
    const torch::Tensor wsum = w.sum(1, true).clamp_min(1e-6);      // [B, 1]
    const torch::Tensor vbar = (w.unsqueeze(2) * v).sum(1) / wsum;  // [B, 3]
    const torch::Tensor pbar = (w.unsqueeze(2) * p).sum(1) / wsum;
    const torch::Tensor dv = v - vbar.unsqueeze(1), dp = p - pbar.unsqueeze(1);
    const torch::Tensor S = torch::einsum("bn,bni,bnj->bij", {w, dp, dv});  // sum w dp dv^T
    const torch::Tensor c = S.select(1, 0).select(1, 0) + S.select(1, 1).select(1, 1);
    const torch::Tensor s = S.select(1, 1).select(1, 0) - S.select(1, 0).select(1, 1);
    const torch::Tensor norm = torch::sqrt(c * c + s * s + 1e-12);
    const torch::Tensor cy = c / norm, sy = s / norm;
    const torch::Tensor zero = torch::zeros_like(cy), one = torch::ones_like(cy);
    TorchSimilarity T;
    T.rotation = torch::stack({cy, -sy, zero, sy, cy, zero, zero, zero, one}, 1).view({-1, 3, 3});
    const torch::Tensor trace = cy * c + sy * s + S.select(1, 2).select(1, 2);
    const torch::Tensor var_v = (w * dv.pow(2).sum(2)).sum(1).clamp_min(1e-9);
    T.scale = trace / var_v;
    T.translation =
        pbar - T.scale.unsqueeze(1) * torch::matmul(T.rotation, vbar.unsqueeze(2)).squeeze(2);
    return T;
}

torch::Tensor volume_tensor(const std::vector<const TsdfVolume*>& volumes) {
    const int r = volumes.front()->grid().resolution;
    torch::Tensor out = torch::empty({static_cast<long>(volumes.size()), 2, r, r, r});
    float* d = out.data_ptr<float>();
    const std::size_t n = volumes.front()->grid().size();
    for (std::size_t b = 0; b < volumes.size(); ++b) {
        const auto& t = volumes[b]->tsdf();
        const auto& w = volumes[b]->weight();
        for (std::size_t i = 0; i < n; ++i) {
            d[(2 * b) * n + i] = t[i];
            d[(2 * b + 1) * n + i] = w[i] / (w[i] + 1.0f);
        }
    }
    return out;
}

torch::Tensor points_tensor(const std::vector<Eigen::Vector3d>& points) {
    torch::Tensor out = torch::empty({static_cast<long>(points.size()), 3});
    float* d = out.data_ptr<float>();
    for (std::size_t i = 0; i < points.size(); ++i)
        for (int a = 0; a < 3; ++a)
            d[3 * i + static_cast<std::size_t>(a)] = static_cast<float>(points[i][a]);
    return out;
}

TorchShapeModel::TorchShapeModel(const ShapeModelParams& params) {
    torch::manual_seed(params.seed);
    for (auto& n : nets) {
        n.fn = CorrespondenceNet(params.correspondence_width);
        n.f0 = SdfDecoder(params.sdf_width);
        n.f1 = OccupancyNet(params.occupancy_width);
        n.mean_code = torch::zeros({kLatentDim});
        n.fn->eval();
        n.f0->eval();
        n.f1->eval();
    }
}

std::unique_ptr<ShapeModel::Impl> create_torch_shape_model(const ShapeModelParams& params) {
    return std::make_unique<TorchShapeModel>(params);
}

std::size_t TorchShapeModel::parameter_count() const {
    std::size_t n = 0;
    for (const auto& c : nets) {
        for (const auto& p : c.fn->parameters()) n += static_cast<std::size_t>(p.numel());
        for (const auto& p : c.f0->parameters()) n += static_cast<std::size_t>(p.numel());
        for (const auto& p : c.f1->parameters()) n += static_cast<std::size_t>(p.numel());
    }
    return n;
}

ClassNets& TorchShapeModel::of(ObjectClass cls) const {
    const int k = shape_class_index(cls);
    if (k < 0) throw std::invalid_argument("no shape networks for this class");
    return nets[static_cast<std::size_t>(k)];
}

namespace {

torch::Tensor params_tensor(const ShapeModelParams& p) {
    return torch::tensor(
        {1.0, static_cast<double>(p.points), static_cast<double>(p.correspondence_width),
         static_cast<double>(p.sdf_width), static_cast<double>(p.occupancy_width),
         static_cast<double>(p.grid.resolution), p.grid.half_extent, p.truncation_cells,
         p.sdf_clamp},
        torch::kFloat64);
}

}  // namespace

void TorchShapeModel::save(const std::filesystem::path& path,
                           const ShapeModelParams& params) const {
    torch::serialize::OutputArchive archive;
    archive.write("makeway_shape_params", params_tensor(params));
    for (std::size_t k = 0; k < 2; ++k) {
        const std::string c = k == 0 ? "chair" : "table";
        torch::serialize::OutputArchive fn, f0, f1;
        nets[k].fn->save(fn);
        nets[k].f0->save(f0);
        nets[k].f1->save(f1);
        archive.write(c + "_fn", fn);
        archive.write(c + "_f0", f0);
        archive.write(c + "_f1", f1);
        archive.write(c + "_mean_code", nets[k].mean_code);
    }
    perception::save_archive_atomically(archive, path);
}

std::unique_ptr<ShapeModel::Impl> load_torch_shape_model(const std::string& bytes,
                                                         const std::filesystem::path& path,
                                                         ShapeModelParams& params) {
    try {
        torch::serialize::InputArchive archive;
        archive.load_from(bytes.data(), bytes.size());
        torch::Tensor t;
        if (!archive.try_read("makeway_shape_params", t) || t.numel() != 9)
            throw std::runtime_error("not a makeway shape model (no parameters)");
        const auto v = t.to(torch::kFloat64).contiguous();
        const double* d = v.data_ptr<double>();
        if (d[0] != 1.0) throw std::runtime_error("unknown shape model version");
        ShapeModelParams p;
        p.points = static_cast<int>(d[1]);
        p.correspondence_width = static_cast<int>(d[2]);
        p.sdf_width = static_cast<int>(d[3]);
        p.occupancy_width = static_cast<int>(d[4]);
        p.grid.resolution = static_cast<int>(d[5]);
        p.grid.half_extent = d[6];
        p.truncation_cells = d[7];
        p.sdf_clamp = d[8];
        auto in = [](double x, double lo, double hi) { return x >= lo && x <= hi; };
        if (!in(p.points, 8, 8192) || !in(p.correspondence_width, 4, 1024) ||
            !in(p.sdf_width, kLatentDim + 8, 2048) || !in(p.occupancy_width, 4, 1024) ||
            !in(p.grid.resolution, 4, 128) || p.grid.resolution % 2 != 0 ||
            !in(p.grid.half_extent, 0.5, 4.0) || !in(p.truncation_cells, 0.5, 20) ||
            !in(p.sdf_clamp, 1e-3, 1.0)) {
            throw std::runtime_error("impossible parameters in the file");
        }
        auto model = std::make_unique<TorchShapeModel>(p);
        for (std::size_t k = 0; k < 2; ++k) {
            const std::string c = k == 0 ? "chair" : "table";
            torch::serialize::InputArchive fn, f0, f1;
            archive.read(c + "_fn", fn);
            archive.read(c + "_f0", f0);
            archive.read(c + "_f1", f1);
            model->nets[k].fn->load(fn);
            model->nets[k].f0->load(f0);
            model->nets[k].f1->load(f1);
            torch::Tensor code;
            archive.read(c + "_mean_code", code);
            if (code.numel() != kLatentDim)
                throw std::runtime_error("the mean code has the wrong size");
            model->nets[k].mean_code = code.to(torch::kFloat32).view({kLatentDim}).clone();
            model->nets[k].fn->eval();
            model->nets[k].f0->eval();
            model->nets[k].f1->eval();
        }
        params = p;
        return model;
    } catch (...) {
        perception::rethrow_load_error(path, "shape model");
    }
}

std::vector<float> TorchShapeModel::correspond(ObjectClass cls,
                                               const std::vector<Eigen::Vector3d>& sample) const {
    if (sample.empty()) return {};
    torch::NoGradGuard no_grad;
    const torch::Tensor t = of(cls).fn->forward(points_tensor(sample).unsqueeze(0)).contiguous();
    return std::vector<float>(t.data_ptr<float>(), t.data_ptr<float>() + t.numel());
}

std::vector<float> TorchShapeModel::sdf(ObjectClass cls, const Latent& z,
                                        const std::vector<Eigen::Vector3d>& points) const {
    if (points.empty()) return {};
    torch::NoGradGuard no_grad;
    ClassNets& n = of(cls);
    const torch::Tensor code =
        torch::from_blob(const_cast<float*>(z.data()), {1, kLatentDim}).clone();
    const torch::Tensor in =
        torch::cat({code.expand({static_cast<long>(points.size()), -1}), points_tensor(points)}, 1);
    const torch::Tensor out = n.f0->forward(in).contiguous();
    return std::vector<float>(out.data_ptr<float>(), out.data_ptr<float>() + out.numel());
}

Latent TorchShapeModel::fit_latent(ObjectClass cls, const std::vector<Eigen::Vector3d>& surface,
                                   const std::vector<Eigen::Vector3d>& free, int iterations,
                                   const ShapeModelParams& params) const {
    ClassNets& n = of(cls);
    torch::Tensor code = n.mean_code.clone().unsqueeze(0).set_requires_grad(true);
    Latent out{};
    if (surface.empty() || iterations <= 0) {
        std::copy(n.mean_code.data_ptr<float>(), n.mean_code.data_ptr<float>() + kLatentDim,
                  out.begin());
        return out;
    }
    const torch::Tensor ps = points_tensor(surface),
                        pf = free.empty() ? torch::zeros({0, 3}) : points_tensor(free);
    const auto clamp = static_cast<float>(params.sdf_clamp);
    // Adam on the code alone. torch::autograd::grad asks for the code's gradient only, so the
    // shared decoder's parameters are never written (several threads may fit at once).
    torch::Tensor m = torch::zeros_like(code), v = torch::zeros_like(code);
    const double lr = 0.02, b1 = 0.9, b2 = 0.999;
    for (int it = 1; it <= iterations; ++it) {
        const torch::Tensor ds = n.f0->forward(torch::cat({code.expand({ps.size(0), -1}), ps}, 1));
        torch::Tensor loss = ds.abs().mean() + 1e-3 * code.pow(2).sum();
        if (pf.size(0) > 0) {
            const torch::Tensor df =
                n.f0->forward(torch::cat({code.expand({pf.size(0), -1}), pf}, 1));
            loss = loss + torch::relu(clamp - df).mean();
        }
        const torch::Tensor g = torch::autograd::grad({loss}, {code})[0];
        torch::NoGradGuard no_grad;
        m = b1 * m + (1 - b1) * g;
        v = b2 * v + (1 - b2) * g * g;
        const double c1 = 1 - std::pow(b1, it), c2 = 1 - std::pow(b2, it);
        code.sub_(lr * (m / c1) / (torch::sqrt(v / c2) + 1e-8));
    }
    const torch::Tensor c = code.detach().contiguous();
    std::copy(c.data_ptr<float>(), c.data_ptr<float>() + kLatentDim, out.begin());
    return out;
}

std::vector<float> TorchShapeModel::occupancy(ObjectClass cls, const TsdfVolume& tsdf,
                                              const Latent& z,
                                              const std::vector<Eigen::Vector3d>& points,
                                              const ShapeModelParams& params) const {
    if (points.empty()) return {};
    if (tsdf.grid().resolution != params.grid.resolution)
        throw std::invalid_argument("TSDF volume on another grid than the model's");
    torch::NoGradGuard no_grad;
    ClassNets& n = of(cls);
    const torch::Tensor features = n.f1->encode(volume_tensor({&tsdf}));
    const torch::Tensor code =
        torch::from_blob(const_cast<float*>(z.data()), {1, kLatentDim}).clone();
    const torch::Tensor q =
        (points_tensor(points) / static_cast<float>(params.grid.half_extent)).unsqueeze(0);
    const torch::Tensor out = torch::sigmoid(n.f1->decode(features, code, q)).contiguous();
    return std::vector<float>(out.data_ptr<float>(), out.data_ptr<float>() + out.numel());
}

}  // namespace makeway::shape

// Training F_n, F_0 and F_1 (see shape/shape_training.hpp): the module's side.

#include <algorithm>
#include <chrono>
#include <cmath>

#include "makeway/common/random.hpp"
#include "makeway/neural/shape_nets.hpp"

namespace makeway::shape {

namespace F = torch::nn::functional;

namespace {

// Cosine decay after a 3 % warm-up.
double lr_at(double peak, int step, int steps) {
    const double warm = std::max(1.0, 0.03 * steps);
    if (step < warm) return peak * (step + 1) / warm;
    return peak * 0.5 * (1.0 + std::cos(M_PI * (step - warm) / std::max(1.0, steps - warm)));
}

void set_lr(torch::optim::Adam& opt, double lr) {
    for (auto& g : opt.param_groups()) static_cast<torch::optim::AdamOptions&>(g.options()).lr(lr);
}

struct LossTrace {
    std::vector<double> values;
    NetLoss summary() const {
        NetLoss l;
        if (values.empty()) return l;
        const std::size_t k = std::max<std::size_t>(1, values.size() / 20);
        for (std::size_t i = 0; i < k; ++i)
            l.first += values[i] / static_cast<double>(k),
                l.last += values[values.size() - 1 - i] / static_cast<double>(k);
        return l;
    }
};

constexpr int kMaxSymmetries = 24;

// ---- F_n -------------------------------------------------------------------------------------
NetLoss train_correspondence(
    ClassNets& nets, const ShapeTrainingSet& data, const std::vector<std::size_t>& views,
    const ShapeModelParams& mp, const ShapeTrainParams& p, Rng& rng, const std::string& stage,
    const std::function<void(const std::string&, int, int, double)>& progress) {
    LossTrace trace;
    if (views.empty() || p.correspondence_steps == 0) return {};
    nets.fn->train();
    torch::optim::Adam opt(nets.fn->parameters(), torch::optim::AdamOptions(p.learning_rate));
    const int B = p.correspondence_batch, N = mp.points;
    for (int step = 0; step < p.correspondence_steps; ++step) {
        set_lr(opt, lr_at(p.learning_rate, step, p.correspondence_steps));
        torch::Tensor pts = torch::empty({B, N, 3}), vt = torch::empty({B, N, 3}),
                      inl = torch::empty({B, N});
        torch::Tensor sym = torch::empty({B, kMaxSymmetries, 3, 3}), scale = torch::empty({B});
        float* pp = pts.data_ptr<float>();
        float* pv = vt.data_ptr<float>();
        float* pi = inl.data_ptr<float>();
        float* ps = sym.data_ptr<float>();
        for (int b = 0; b < B; ++b) {
            const ShapeView& view = data.views[views[static_cast<std::size_t>(
                uniform_int(rng, 0, static_cast<std::int64_t>(views.size()) - 1))]];
            const ShapeExample& shape = data.shapes[static_cast<std::size_t>(view.shape)];
            // A random turn of the whole view about the vertical: more poses for free.
            const Eigen::Matrix3d Ra =
                Eigen::AngleAxisd(uniform(rng, -M_PI, M_PI), Eigen::Vector3d::UnitZ())
                    .toRotationMatrix();
            Similarity3 truth = view.truth;
            truth.rotation = Ra * truth.rotation;
            truth.translation = Ra * truth.translation;
            scale[b] = static_cast<float>(truth.scale);
            for (int i = 0; i < N; ++i) {
                const auto k = static_cast<std::size_t>(
                    uniform_int(rng, 0, static_cast<std::int64_t>(view.points.size()) - 1));
                const Eigen::Vector3d q = Ra * view.points[k];
                const Eigen::Vector3d v = truth.inverse_apply(q);
                for (int a = 0; a < 3; ++a)
                    pp[(b * N + i) * 3 + a] = static_cast<float>(q[a]),
                                         pv[(b * N + i) * 3 + a] = static_cast<float>(v[a]);
                pi[b * N + i] = view.outlier[k] ? 0.0f : 1.0f;
            }
            for (int s = 0; s < kMaxSymmetries; ++s) {
                const double yaw =
                    shape.symmetry_yaws[static_cast<std::size_t>(s) % shape.symmetry_yaws.size()];
                const Eigen::Matrix3d R =
                    Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
                for (int r = 0; r < 3; ++r)
                    for (int c = 0; c < 3; ++c)
                        ps[((b * kMaxSymmetries + s) * 3 + r) * 3 + c] =
                            static_cast<float>(R(r, c));
            }
        }
        const torch::Tensor out = nets.fn->forward(pts);
        const torch::Tensor v = out.slice(2, 0, 3), logit = out.select(2, 3);
        // Targets under every symmetry [B, K, N, 3]; the nearest one per view is taught.
        const torch::Tensor targets = torch::einsum("bkij,bnj->bkni", {sym, vt});
        const torch::Tensor inl_count = inl.sum(1).clamp_min(1.0);
        const torch::Tensor err =
            ((v.unsqueeze(1) - targets).abs().sum(3) * inl.unsqueeze(1)).sum(2) /
            inl_count.unsqueeze(1);  // [B, K]
        const auto [coord, best] = err.min(1);
        const torch::Tensor chosen = targets.index({torch::arange(B), best});  // [B, N, 3]
        // The solve from the predictions, judged by where it puts the chosen targets.
        const torch::Tensor w = torch::sigmoid(logit);
        const TorchSimilarity T = solve_upright_similarity(v, pts, w);
        const torch::Tensor pose =
            ((T.apply(chosen) - pts).abs().sum(2) * inl).sum(1) / inl_count / scale;
        const torch::Tensor conf = F::binary_cross_entropy_with_logits(logit, inl);
        const torch::Tensor loss = coord.mean() + pose.clamp_max(1.0).mean() + 0.3 * conf;
        opt.zero_grad();
        loss.backward();
        torch::nn::utils::clip_grad_norm_(nets.fn->parameters(), 5.0);
        opt.step();
        trace.values.push_back(loss.item<double>());
        if (progress) progress(stage, step + 1, p.correspondence_steps, trace.values.back());
    }
    nets.fn->eval();
    return trace.summary();
}

// ---- F_0 -------------------------------------------------------------------------------------
NetLoss train_sdf(ClassNets& nets, torch::Tensor& codes, const ShapeTrainingSet& data,
                  const std::vector<std::size_t>& shapes, const ShapeModelParams& mp,
                  const ShapeTrainParams& p, Rng& rng, const std::string& stage,
                  const std::function<void(const std::string&, int, int, double)>& progress) {
    LossTrace trace;
    codes = torch::randn({static_cast<long>(shapes.size()), kLatentDim}) * 0.01;
    codes.set_requires_grad(true);
    if (shapes.empty() || p.sdf_steps == 0) return {};
    nets.f0->train();
    torch::optim::Adam opt(nets.f0->parameters(), torch::optim::AdamOptions(p.learning_rate));
    torch::optim::Adam code_opt({codes}, torch::optim::AdamOptions(p.learning_rate));
    const int S = std::min<int>(p.sdf_batch_shapes, static_cast<int>(shapes.size())),
              M = p.sdf_samples;
    const auto clamp = static_cast<float>(mp.sdf_clamp);
    for (int step = 0; step < p.sdf_steps; ++step) {
        const double lr = lr_at(p.learning_rate, step, p.sdf_steps);
        set_lr(opt, lr);
        set_lr(code_opt, lr);
        torch::Tensor xyz = torch::empty({S * M, 3}), target = torch::empty({S * M, 1});
        std::vector<long> which(static_cast<std::size_t>(S * M));
        float* px = xyz.data_ptr<float>();
        float* pt = target.data_ptr<float>();
        for (int s = 0; s < S; ++s) {
            const auto local = static_cast<std::size_t>(
                uniform_int(rng, 0, static_cast<std::int64_t>(shapes.size()) - 1));
            const ShapeExample& shape = data.shapes[shapes[local]];
            for (int i = 0; i < M; ++i) {
                const auto k = static_cast<std::size_t>(
                    uniform_int(rng, 0, static_cast<std::int64_t>(shape.sdf.size()) - 1));
                const std::size_t row = static_cast<std::size_t>(s * M + i);
                for (int a = 0; a < 3; ++a)
                    px[row * 3 + static_cast<std::size_t>(a)] = shape.sdf_points[k][a];
                pt[row] = std::clamp(shape.sdf[k], -clamp, clamp);
                which[row] = static_cast<long>(local);
            }
        }
        const torch::Tensor z = codes.index({torch::tensor(which)});
        const torch::Tensor pred = nets.f0->forward(torch::cat({z, xyz}, 1)).clamp(-clamp, clamp);
        const torch::Tensor loss = (pred - target).abs().mean() + 1e-4 * z.pow(2).sum(1).mean();
        opt.zero_grad();
        code_opt.zero_grad();
        loss.backward();
        opt.step();
        code_opt.step();
        trace.values.push_back(loss.item<double>());
        if (progress) progress(stage, step + 1, p.sdf_steps, trace.values.back());
    }
    nets.f0->eval();
    codes = codes.detach();
    nets.mean_code = codes.mean(0).contiguous();
    return trace.summary();
}

// ---- F_1 -------------------------------------------------------------------------------------
NetLoss train_occupancy(ClassNets& nets, const torch::Tensor& codes, const ShapeTrainingSet& data,
                        const std::vector<std::size_t>& shapes,
                        const std::vector<std::vector<std::size_t>>& views_of_shape,
                        const ShapeModelParams& mp, const ShapeTrainParams& p, Rng& rng,
                        const std::string& stage,
                        const std::function<void(const std::string&, int, int, double)>& progress) {
    LossTrace trace;
    if (shapes.empty() || p.occupancy_steps == 0) return {};
    // TSDF volumes fused in each shape's canonical frame from 1-3 of its views, at their true pose
    // disturbed by what F_n's pose error looks like (a few degrees, a few centimetres).
    struct Fused {
        std::size_t local = 0;
        TsdfVolume volume;
    };
    std::vector<Fused> fused;
    for (std::size_t local = 0; local < shapes.size(); ++local) {
        const auto& vs = views_of_shape[local];
        if (vs.empty()) continue;
        for (int f = 0; f < p.fusions_per_shape; ++f) {
            Fused item{local, TsdfVolume(mp.grid, mp.truncation_cells)};
            const int count = static_cast<int>(uniform_int(rng, 1, 3));
            for (int c = 0; c < count; ++c) {
                const ShapeView& view = data.views[vs[static_cast<std::size_t>(
                    uniform_int(rng, 0, static_cast<std::int64_t>(vs.size()) - 1))]];
                Similarity3 T = view.truth;
                T.rotation = Eigen::AngleAxisd(normal(rng, 0.0, 0.05), Eigen::Vector3d::UnitZ())
                                 .toRotationMatrix() *
                             T.rotation;
                T.translation += Eigen::Vector3d(normal(rng, 0, 0.02), normal(rng, 0, 0.02),
                                                 normal(rng, 0, 0.01));
                std::vector<Eigen::Vector3d> canonical;
                for (const auto& q : view.points) canonical.push_back(T.inverse_apply(q));
                item.volume.integrate(canonical, T.inverse_apply(view.origin));
            }
            fused.push_back(std::move(item));
        }
    }
    if (fused.empty()) return {};
    nets.f1->train();
    torch::optim::Adam opt(nets.f1->parameters(), torch::optim::AdamOptions(p.learning_rate));
    const int B = p.occupancy_batch, M = p.occupancy_samples;
    const float code_std = codes.std().item<float>();
    for (int step = 0; step < p.occupancy_steps; ++step) {
        set_lr(opt, lr_at(p.learning_rate, step, p.occupancy_steps));
        std::vector<const TsdfVolume*> volumes;
        torch::Tensor q = torch::empty({B, M, 3}), target = torch::empty({B, M}),
                      z = torch::empty({B, kLatentDim});
        float* pq = q.data_ptr<float>();
        float* pt = target.data_ptr<float>();
        for (int b = 0; b < B; ++b) {
            const Fused& item = fused[static_cast<std::size_t>(
                uniform_int(rng, 0, static_cast<std::int64_t>(fused.size()) - 1))];
            volumes.push_back(&item.volume);
            const ShapeExample& shape = data.shapes[shapes[item.local]];
            for (int i = 0; i < M; ++i) {
                const auto k = static_cast<std::size_t>(
                    uniform_int(rng, 0, static_cast<std::int64_t>(shape.occupied.size()) - 1));
                for (int a = 0; a < 3; ++a)
                    pq[(b * M + i) * 3 + a] =
                        shape.occupancy_points[k][a] / static_cast<float>(mp.grid.half_extent);
                pt[b * M + i] = shape.occupied[k] ? 1.0f : 0.0f;
            }
            // The shape's own F_0 code, blurred (a code fitted to a partial view is not exact), or
            // the mean code a quarter of the time: the TSDF has to carry what the code does not.
            torch::Tensor code = bernoulli(rng, 0.25)
                                     ? nets.mean_code.clone()
                                     : codes[static_cast<long>(item.local)] +
                                           0.5f * code_std * torch::randn({kLatentDim});
            z[b] = code;
        }
        const torch::Tensor logits = nets.f1->decode(nets.f1->encode(volume_tensor(volumes)), z, q);
        // The occupancy loss of the supplementary (binary cross-entropy), averaged.
        const torch::Tensor loss = F::binary_cross_entropy_with_logits(logits, target);
        opt.zero_grad();
        loss.backward();
        opt.step();
        trace.values.push_back(loss.item<double>());
        if (progress) progress(stage, step + 1, p.occupancy_steps, trace.values.back());
    }
    nets.f1->eval();
    return trace.summary();
}

}  // namespace

ShapeTrainReport train_torch_shape_model(
    ShapeModel::Impl& networks, const ShapeModelParams& model, const ShapeTrainingSet& data,
    const ShapeTrainParams& p,
    const std::function<void(const std::string&, int, int, double)>& progress) {
    const auto t0 = std::chrono::steady_clock::now();
    torch::manual_seed(p.seed);
    Rng rng = make_rng(p.seed, 1919);
    ShapeTrainReport report;
    for (int k = 0; k < 2; ++k) {
        const ObjectClass cls = k == 0 ? ObjectClass::kChair : ObjectClass::kTable;
        const std::string name = k == 0 ? "chair" : "table";
        std::vector<std::size_t> shapes, views;
        std::vector<long> local_of(data.shapes.size(), -1);
        for (std::size_t s = 0; s < data.shapes.size(); ++s) {
            if (data.shapes[s].cls != cls || data.shapes[s].sdf.empty() ||
                data.shapes[s].occupied.empty())
                continue;
            local_of[s] = static_cast<long>(shapes.size());
            shapes.push_back(s);
        }
        std::vector<std::vector<std::size_t>> views_of_shape(shapes.size());
        for (std::size_t v = 0; v < data.views.size(); ++v) {
            const ShapeView& view = data.views[v];
            if (view.shape < 0 || static_cast<std::size_t>(view.shape) >= data.shapes.size() ||
                local_of[static_cast<std::size_t>(view.shape)] < 0)
                continue;
            if (view.points.size() < 3 || view.outlier.size() != view.points.size()) continue;
            views.push_back(v);
            views_of_shape[static_cast<std::size_t>(local_of[static_cast<std::size_t>(view.shape)])]
                .push_back(v);
        }
        ClassNets& nets = torch_nets(networks)[static_cast<std::size_t>(k)];
        auto ts = std::chrono::steady_clock::now();
        auto lap = [&](int stage) {
            const auto now = std::chrono::steady_clock::now();
            report.stage_seconds[stage] += std::chrono::duration<double>(now - ts).count();
            ts = now;
        };
        report.correspondence[k] =
            train_correspondence(nets, data, views, model, p, rng, name + " F_n", progress);
        lap(0);
        torch::Tensor codes;
        report.sdf[k] =
            train_sdf(nets, codes, data, shapes, model, p, rng, name + " F_0", progress);
        lap(1);
        report.occupancy[k] = train_occupancy(nets, codes, data, shapes, views_of_shape, model, p,
                                              rng, name + " F_1", progress);
        lap(2);
    }
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return report;
}

}  // namespace makeway::shape

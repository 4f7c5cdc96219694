// Training the detector: CenterNet targets on the output grid, focal loss on the heatmaps, L1 on
// the box terms at object centres, AdamW with warm-up and cosine decay, augmentation on the points.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "makeway/common/angles.hpp"
#include "makeway/common/random.hpp"
#include "makeway/neural/detector_net.hpp"
#include "makeway/perception/levelling.hpp"
#include "makeway/perception/training_augment.hpp"

namespace makeway::perception {

namespace {

using Boxes = LabelledBoxes;

// Heatmaps (Gaussian per object) and box targets at the centre cells.
void make_targets(const Boxes& boxes, const BevGridParams& g, float* heat, float* reg,
                  float* mask) {
    const int n = g.out_cells();
    const double oc = g.out_cell_m();
    const auto plane = static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
    for (const auto& [cls, b] : boxes) {
        const double fx = (b.centre_m.x() + g.range_m) / oc, fy = (b.centre_m.y() + g.range_m) / oc;
        const int ix = static_cast<int>(std::floor(fx)), iy = static_cast<int>(std::floor(fy));
        if (ix < 0 || iy < 0 || ix >= n || iy >= n) continue;
        const double sigma = std::max(0.8, 0.25 * std::min(b.size_m.x(), b.size_m.y()) / oc);
        const int r = static_cast<int>(std::ceil(3 * sigma));
        float* h = heat + static_cast<std::size_t>(cls) * plane;
        for (int y = std::max(0, iy - r); y <= std::min(n - 1, iy + r); ++y) {
            for (int x = std::max(0, ix - r); x <= std::min(n - 1, ix + r); ++x) {
                const auto v = static_cast<float>(
                    std::exp(-((x - ix) * (x - ix) + (y - iy) * (y - iy)) / (2 * sigma * sigma)));
                float& cell = h[static_cast<std::size_t>(y * n + x)];
                cell = std::max(cell, v);
            }
        }
        // Tables are symmetric under a half turn: their yaw is taught in (-pi/2, pi/2].
        double yaw = b.yaw_rad;
        if (cls == ObjectClass::kTable) yaw = wrap_angle(2 * yaw) / 2;
        const float t[8] = {static_cast<float>(fx - ix),
                            static_cast<float>(fy - iy),
                            static_cast<float>(b.centre_m.z()),
                            static_cast<float>(std::log(b.size_m.x())),
                            static_cast<float>(std::log(b.size_m.y())),
                            static_cast<float>(std::log(b.size_m.z())),
                            static_cast<float>(std::sin(yaw)),
                            static_cast<float>(std::cos(yaw))};
        const auto cell = static_cast<std::size_t>(iy * n + ix);
        for (int k = 0; k < 8; ++k) reg[static_cast<std::size_t>(k) * plane + cell] = t[k];
        mask[cell] = 1.0f;
    }
}

struct Losses {
    torch::Tensor heat, box;
};

Losses losses(const torch::Tensor& raw, const torch::Tensor& heat, const torch::Tensor& reg,
              const torch::Tensor& mask) {
    const torch::Tensor p =
        torch::sigmoid(raw.slice(1, 0, kNumObjectClasses)).clamp(1e-4, 1 - 1e-4);
    const torch::Tensor pos = heat.eq(1.0).to(torch::kFloat32);
    const torch::Tensor num_pos = pos.sum().clamp_min(1.0);
    // CenterNet focal loss (alpha 2, beta 4).
    const torch::Tensor pos_loss = (torch::log(p) * (1 - p).pow(2) * pos).sum();
    const torch::Tensor neg_loss =
        (torch::log(1 - p) * p.pow(2) * (1 - heat).pow(4) * (1 - pos)).sum();
    Losses l;
    l.heat = -(pos_loss + neg_loss) / num_pos;
    const torch::Tensor m = mask.unsqueeze(1);
    l.box =
        (torch::abs(raw.slice(1, kNumObjectClasses) - reg) * m).sum() / (m.sum().clamp_min(1.0));
    return l;
}

}  // namespace

std::vector<EpochReport> train_torch_detector(
    Detector::Impl& network, const DetectorParams& detector,
    const std::vector<TrainingSample>& samples, const TrainParams& params,
    const std::function<void(int, int, double)>& progress,
    const std::function<void(const EpochReport&)>& on_epoch) {
    std::vector<EpochReport> reports;
    if (samples.empty()) return reports;
    torch::manual_seed(params.seed);
    CenterNet& net = torch_net(network);
    const BevGridParams& g = detector.grid;
    torch::optim::AdamW optimizer(
        net->parameters(),
        torch::optim::AdamWOptions(params.learning_rate).weight_decay(params.weight_decay));
    int start_epoch = 0;
    if (!params.checkpoint.empty() && params.checkpoint.has_parent_path())
        std::filesystem::create_directories(params.checkpoint.parent_path());
    if (!params.checkpoint.empty() && std::filesystem::exists(params.checkpoint)) {
        torch::serialize::InputArchive archive;
        archive.load_from(params.checkpoint.string());
        torch::serialize::InputArchive model, optim;
        archive.read("model", model);
        archive.read("optimizer", optim);
        net->load(model);
        optimizer.load(optim);
        torch::Tensor e;
        archive.read("epoch", e);
        start_epoch = static_cast<int>(e.item<std::int64_t>());
    }
    const int batches =
        static_cast<int>((samples.size() + static_cast<std::size_t>(params.batch_size) - 1) /
                         static_cast<std::size_t>(params.batch_size));
    const int steps = batches * params.epochs;
    const int warmup = std::max(1, steps / 20);
    const int n = g.out_cells(), c = g.channels(), cells = g.cells();
    for (int epoch = start_epoch; epoch < params.epochs; ++epoch) {
        net->train();
        Rng rng =
            make_rng(params.seed,
                     1000 + static_cast<std::uint64_t>(epoch));  // resumable: one stream per epoch
        std::vector<std::size_t> order(samples.size());
        std::iota(order.begin(), order.end(), 0);
        for (std::size_t i = order.size(); i > 1; --i)
            std::swap(order[i - 1], order[static_cast<std::size_t>(
                                        uniform_int(rng, 0, static_cast<std::int64_t>(i) - 1))]);
        EpochReport report{.epoch = epoch + 1};
        for (int b = 0; b < batches; ++b) {
            const std::size_t begin =
                static_cast<std::size_t>(b) * static_cast<std::size_t>(params.batch_size);
            const std::size_t count =
                std::min(samples.size() - begin, static_cast<std::size_t>(params.batch_size));
            const auto bs = static_cast<std::int64_t>(count);
            torch::Tensor bev = torch::zeros({bs, c, cells, cells});
            torch::Tensor heat = torch::zeros({bs, kNumObjectClasses, n, n}),
                          reg = torch::zeros({bs, 8, n, n}), mask = torch::zeros({bs, n, n});
            for (std::size_t i = 0; i < count; ++i) {
                const TrainingSample& s = samples[order[begin + i]];
                PointCloud cloud = *s.cloud_sensor;
                Boxes boxes = s.boxes;
                // The network learns from a level sensor at the height detect() levels to.
                if (const auto T = level_frame_if(s.ground_plane_sensor, detector.level_height_m)) {
                    cloud = cloud.transformed(*T);
                    for (auto& [cls, box] : boxes) box = box.transformed(*T);
                }
                if (params.augment) augment_sample(cloud, boxes, rng);
                const std::vector<float> x = encode_bev(cloud, g);
                std::copy(x.begin(), x.end(), bev[static_cast<std::int64_t>(i)].data_ptr<float>());
                make_targets(boxes, g, heat[static_cast<std::int64_t>(i)].data_ptr<float>(),
                             reg[static_cast<std::int64_t>(i)].data_ptr<float>(),
                             mask[static_cast<std::int64_t>(i)].data_ptr<float>());
            }
            const int step = epoch * batches + b;
            const double lr =
                step < warmup
                    ? params.learning_rate * (step + 1) / warmup
                    : 0.5 * params.learning_rate *
                          (1 + std::cos(kPi * (step - warmup) / std::max(1, steps - warmup)));
            for (auto& group : optimizer.param_groups())
                static_cast<torch::optim::AdamWOptions&>(group.options()).lr(lr);
            optimizer.zero_grad();
            const Losses l = losses(net->forward(bev), heat, reg, mask);
            const torch::Tensor loss = l.heat + l.box;
            loss.backward();
            optimizer.step();
            report.heatmap_loss += l.heat.item<double>() / batches;
            report.box_loss += l.box.item<double>() / batches;
            if (progress) progress(step + 1, steps, loss.item<double>());
        }
        report.mean_loss = report.heatmap_loss + report.box_loss;
        net->eval();
        if (!params.checkpoint.empty()) {
            torch::serialize::OutputArchive archive, model, optim;
            net->save(model);
            optimizer.save(optim);
            archive.write("model", model);
            archive.write("optimizer", optim);
            archive.write("epoch", torch::tensor(static_cast<std::int64_t>(epoch + 1)));
            const std::string tmp = params.checkpoint.string() + ".tmp";
            archive.save_to(tmp);
            std::filesystem::rename(tmp, params.checkpoint);
        }
        reports.push_back(report);
        if (on_epoch) on_epoch(report);
    }
    net->eval();
    return reports;
}

}  // namespace makeway::perception

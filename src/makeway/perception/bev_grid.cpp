#include "makeway/perception/bev_grid.hpp"

#include <algorithm>
#include <cmath>

#include "makeway/perception/nms.hpp"

namespace makeway::perception {

std::vector<std::string> BevGridParams::validate() const {
    std::vector<std::string> p;
    if (!(range_m > 0.5 && range_m <= 50.0)) p.push_back("range_m must be in (0.5, 50]");
    if (!(cell_m > 0.01 && cell_m <= 1.0)) p.push_back("cell_m must be in (0.01, 1]");
    if (!(z_max_m > z_min_m)) p.push_back("need z_min_m < z_max_m");
    if (height_slices < 1 || height_slices > 64) p.push_back("height_slices must be in [1, 64]");
    if (output_stride < 1 || output_stride > 8 || cells() % output_stride != 0)
        p.push_back("output_stride must divide the grid");
    return p;
}

std::vector<float> encode_bev(const PointCloud& cloud, const BevGridParams& g) {
    const int n = g.cells(), c = g.channels();
    const auto plane = static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
    std::vector<float> out(static_cast<std::size_t>(c) * plane, 0.0f);
    std::vector<float> intensity_sum(plane, 0.0f), count(plane, 0.0f);
    const double slice = (g.z_max_m - g.z_min_m) / g.height_slices;
    const bool has_intensity = g.intensity && cloud.intensity.size() == cloud.size();
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const Eigen::Vector3f& p = cloud.xyz[i];
        if (!p.allFinite() || p.z() < g.z_min_m || p.z() >= g.z_max_m) continue;
        const int ix = static_cast<int>(std::floor((p.x() + g.range_m) / g.cell_m));
        const int iy = static_cast<int>(std::floor((p.y() + g.range_m) / g.cell_m));
        if (ix < 0 || iy < 0 || ix >= n || iy >= n) continue;
        const auto cell = static_cast<std::size_t>(iy) * static_cast<std::size_t>(n) +
                          static_cast<std::size_t>(ix);
        const int s = std::min(g.height_slices - 1, static_cast<int>((p.z() - g.z_min_m) / slice));
        out[static_cast<std::size_t>(s) * plane + cell] += 1.0f;
        const float h = static_cast<float>((p.z() - g.z_min_m) / (g.z_max_m - g.z_min_m));
        float& top = out[static_cast<std::size_t>(g.height_slices) * plane + cell];
        top = std::max(top, h);
        count[cell] += 1.0f;
        if (has_intensity) intensity_sum[cell] += cloud.intensity[i];
    }
    for (std::size_t k = 0; k < static_cast<std::size_t>(g.height_slices) * plane; ++k)
        out[k] = std::log1p(out[k]);
    for (std::size_t cell = 0; g.intensity && cell < plane; ++cell) {
        if (count[cell] > 0)
            out[static_cast<std::size_t>(g.height_slices + 1) * plane + cell] =
                intensity_sum[cell] / count[cell];
    }
    return out;
}

std::vector<Detection> decode_heads(const std::vector<float>& heads, const BevGridParams& g,
                                    const DecodeParams& params) {
    const int n = g.out_cells();
    const auto plane = static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
    std::vector<Detection> candidates;
    if (heads.size() != static_cast<std::size_t>(kHeadChannels) * plane) return candidates;
    auto at = [&](int ch, int iy, int ix) {
        return heads[static_cast<std::size_t>(ch) * plane + static_cast<std::size_t>(iy * n + ix)];
    };
    for (int cls = 0; cls < kNumObjectClasses; ++cls) {
        for (int iy = 0; iy < n; ++iy) {
            for (int ix = 0; ix < n; ++ix) {
                const float v = at(cls, iy, ix);
                if (v < params.score_threshold) continue;
                bool peak = true;  // 3x3 local maximum (ties: the first in scan order wins)
                for (int dy = -1; dy <= 1 && peak; ++dy) {
                    for (int dx = -1; dx <= 1 && peak; ++dx) {
                        const int y = iy + dy, x = ix + dx;
                        if ((dx || dy) && y >= 0 && x >= 0 && y < n && x < n) {
                            const float w = at(cls, y, x);
                            peak = w < v || (w == v && (dy > 0 || (dy == 0 && dx > 0)));
                        }
                    }
                }
                if (!peak) continue;
                Detection d;
                d.cls = static_cast<ObjectClass>(cls);
                d.score = v;
                double total = 0.0;
                for (int c = 0; c < kNumObjectClasses; ++c) total += at(c, iy, ix);
                for (int c = 0; c < kNumObjectClasses; ++c)
                    d.class_probabilities[static_cast<std::size_t>(c)] = at(c, iy, ix) / total;
                const int base = kNumObjectClasses;
                const double cx = (ix + at(base, iy, ix)) * g.out_cell_m() - g.range_m;
                const double cy = (iy + at(base + 1, iy, ix)) * g.out_cell_m() - g.range_m;
                d.box_sensor.centre_m = {cx, cy, at(base + 2, iy, ix)};
                d.box_sensor.size_m = {std::exp(at(base + 3, iy, ix)),
                                       std::exp(at(base + 4, iy, ix)),
                                       std::exp(at(base + 5, iy, ix))};
                d.box_sensor.yaw_rad = std::atan2(at(base + 6, iy, ix), at(base + 7, iy, ix));
                const Eigen::Vector3d& size = d.box_sensor.size_m;
                const bool sane =
                    std::isfinite(d.score) && d.box_sensor.centre_m.allFinite() &&
                    std::isfinite(d.box_sensor.yaw_rad) && size.minCoeff() >= params.min_size_m &&
                    size.maxCoeff() <= params.max_size_m && std::isfinite(total) && total > 0.0;
                if (sane) candidates.push_back(d);
            }
        }
    }
    std::sort(candidates.begin(), candidates.end(),
              [](const Detection& a, const Detection& b) { return a.score > b.score; });
    if (static_cast<int>(candidates.size()) > params.max_candidates)
        candidates.resize(static_cast<std::size_t>(params.max_candidates));
    return rotated_nms(std::move(candidates), {.max_bev_iou = params.nms_bev_iou});
}

}  // namespace makeway::perception

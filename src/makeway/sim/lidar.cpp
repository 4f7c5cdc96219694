#include "makeway/sim/lidar.hpp"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "makeway/common/angles.hpp"
#include "makeway/common/random.hpp"

namespace makeway::sim {
namespace {

// Return strength by surface class (unitless, 0..255 like Velodyne's calibrated reflectivity).
float reflectivity(SemanticLabel label) {
    switch (label) {
        case SemanticLabel::kGround: return 20.0f;
        case SemanticLabel::kCeiling: return 40.0f;
        case SemanticLabel::kStructure: return 60.0f;
        case SemanticLabel::kChair: return 35.0f;
        case SemanticLabel::kTable: return 80.0f;
        case SemanticLabel::kPerson: return 15.0f;
        default: return 50.0f;
    }
}

struct ColumnOutput {
    std::vector<Eigen::Vector3f> xyz;
    std::vector<float> intensity;
    std::vector<std::uint16_t> ring;
    std::vector<std::uint8_t> label;
    std::vector<std::uint32_t> instance;
};

}  // namespace

const std::vector<double>& vlp32c_elevations_deg() {
    static const std::vector<double> kAngles{
        -25.0,  -15.639, -11.31, -8.843, -7.254, -6.148, -5.333, -4.667, -4.0,  -3.667, -3.333,
        -3.0,   -2.667,  -2.333, -2.0,   -1.667, -1.333, -1.0,   -0.667, -0.333, 0.0,   0.333,
        0.667,  1.0,     1.333,  1.667,  2.333,  3.333,  4.667,  7.0,    10.333, 15.0};
    return kAngles;
}

int LidarParams::num_columns() const {
    return static_cast<int>(std::lround(360.0 / azimuth_step_deg));
}

std::vector<std::string> LidarParams::validate() const {
    std::vector<std::string> p;
    if (elevations_deg.empty() || elevations_deg.size() > 256) p.push_back("elevations_deg must hold 1..256 angles");
    for (double e : elevations_deg) {
        if (!(e > -90.0 && e < 90.0)) p.push_back("elevations_deg must lie in (-90, 90)");
    }
    if (!(azimuth_step_deg >= 0.01 && azimuth_step_deg <= 10.0)) p.push_back("azimuth_step_deg must be in [0.01, 10]");
    if (!(rate_hz >= 1.0 && rate_hz <= 50.0)) p.push_back("rate_hz must be in [1, 50]");
    if (!(min_range_m >= 0.0 && min_range_m < max_range_m)) p.push_back("min_range_m must be in [0, max_range_m)");
    if (!(max_range_m > 0.0 && max_range_m <= 1000.0)) p.push_back("max_range_m must be in (0, 1000]");
    if (!(range_noise_m >= 0.0 && range_noise_m <= 1.0)) p.push_back("range_noise_m must be in [0, 1]");
    if (!(dropout >= 0.0 && dropout <= 1.0)) p.push_back("dropout must be in [0, 1]");
    if (time_slices < 1 || time_slices > 3600) p.push_back("time_slices must be in [1, 3600]");
    if (num_threads < 1 || num_threads > 256) p.push_back("num_threads must be in [1, 256]");
    return p;
}

PointCloud simulate_sweep(World& world, const LidarParams& params, const PoseAtTime& T_world_sensor_at,
                          double t_start_s, std::uint64_t seed, std::uint64_t sweep_index,
                          SweepStats* stats) {
    const int columns = params.num_columns();
    const int beams = params.num_beams();
    const double dt_column = params.sweep_duration_s() / columns;
    std::vector<Eigen::Vector3f> beam_dirs(beams);  // at azimuth 0, sensor frame
    std::vector<float> cos_el(beams), sin_el(beams);
    for (int b = 0; b < beams; ++b) {
        const double el = deg_to_rad(params.elevations_deg[b]);
        cos_el[b] = static_cast<float>(std::cos(el));
        sin_el[b] = static_cast<float>(std::sin(el));
    }
    std::vector<ColumnOutput> out(columns);
    const std::uint64_t stream = seed ^ (sweep_index * 0xA24BAED4963EE407ULL);

    auto cast_column = [&](int c) {
        const double t_rel = c * dt_column;
        const Isometry3 T_world_sensor = T_world_sensor_at(t_start_s + t_rel);
        const Eigen::Matrix3f R = T_world_sensor.linear().cast<float>();
        const Eigen::Vector3f origin = T_world_sensor.translation().cast<float>();
        const double az = deg_to_rad(c * params.azimuth_step_deg);
        const float ca = static_cast<float>(std::cos(az)), sa = static_cast<float>(std::sin(az));
        std::vector<Eigen::Vector3f> dirs_sensor(beams), dirs_world(beams);
        for (int b = 0; b < beams; ++b) {
            dirs_sensor[b] = Eigen::Vector3f(cos_el[b] * ca, cos_el[b] * sa, sin_el[b]);
            dirs_world[b] = R * dirs_sensor[b];
        }
        std::vector<RayHit> hits(beams);
        const auto max_range = static_cast<float>(params.max_range_m);
        if (params.use_packets) {
            for (int b0 = 0; b0 < beams; b0 += 8) {
                bool valid[8];
                Eigen::Vector3f d8[8];
                RayHit h8[8];
                for (int i = 0; i < 8; ++i) {
                    valid[i] = b0 + i < beams;
                    d8[i] = valid[i] ? dirs_world[b0 + i] : Eigen::Vector3f::UnitX();
                }
                world.cast8(origin, d8, max_range, valid, h8);
                for (int i = 0; i < 8 && b0 + i < beams; ++i) hits[b0 + i] = h8[i];
            }
        } else {
            for (int b = 0; b < beams; ++b) hits[b] = world.cast(origin, dirs_world[b], max_range);
        }
        ColumnOutput& o = out[c];
        for (int b = 0; b < beams; ++b) {
            if (!hits[b].hit) continue;
            const std::uint64_t ray_id = static_cast<std::uint64_t>(c) * beams + b;
            if (counter_uniform(stream, 2 * ray_id) < params.dropout) continue;
            const double range = hits[b].range_m + params.range_noise_m * counter_normal(stream, 2 * ray_id + 1);
            if (range < params.min_range_m || range > params.max_range_m) continue;
            o.xyz.push_back(static_cast<float>(range) * dirs_sensor[b]);
            o.intensity.push_back(reflectivity(hits[b].label) * std::clamp(1.0f - hits[b].range_m / 60.0f, 0.2f, 1.0f));
            o.ring.push_back(static_cast<std::uint16_t>(b));
            o.label.push_back(static_cast<std::uint8_t>(hits[b].label));
            o.instance.push_back(hits[b].instance);
        }
    };

    std::unique_ptr<tbb::global_control> limit;
    if (params.num_threads > 1) {
        limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                      static_cast<std::size_t>(params.num_threads));
    }
    const int slices = std::min(params.time_slices, columns);
    for (int s = 0; s < slices; ++s) {
        const int c0 = s * columns / slices, c1 = (s + 1) * columns / slices;
        world.set_time(t_start_s + 0.5 * (c0 + c1) * dt_column);
        if (params.num_threads > 1) {
            tbb::parallel_for(tbb::blocked_range<int>(c0, c1, 16), [&](const tbb::blocked_range<int>& r) {
                for (int c = r.begin(); c < r.end(); ++c) cast_column(c);
            });
        } else {
            for (int c = c0; c < c1; ++c) cast_column(c);
        }
    }

    // Gather in firing order (column-major), so output never depends on the thread schedule.
    PointCloud cloud;
    std::size_t n = 0;
    for (const auto& o : out) n += o.xyz.size();
    cloud.xyz.reserve(n);
    for (int c = 0; c < columns; ++c) {
        const ColumnOutput& o = out[c];
        cloud.xyz.insert(cloud.xyz.end(), o.xyz.begin(), o.xyz.end());
        cloud.intensity.insert(cloud.intensity.end(), o.intensity.begin(), o.intensity.end());
        cloud.ring.insert(cloud.ring.end(), o.ring.begin(), o.ring.end());
        cloud.time_s.insert(cloud.time_s.end(), o.xyz.size(), static_cast<float>(c * dt_column));
        cloud.label.insert(cloud.label.end(), o.label.begin(), o.label.end());
        cloud.instance.insert(cloud.instance.end(), o.instance.begin(), o.instance.end());
    }
    if (stats) {
        stats->rays = static_cast<std::size_t>(columns) * beams;
        stats->returns = n;
    }
    return cloud;
}

}  // namespace makeway::sim

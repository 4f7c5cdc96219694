#include "makeway/sim/lidar.hpp"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <tuple>

#include "makeway/common/angles.hpp"
#include "makeway/common/random.hpp"
#include "makeway/sim/param_tables.hpp"

namespace makeway::sim {
namespace {

// The return's intensity as a Velodyne reports it (0..255): the surface's reflectivity, weakened
// by the incidence angle (Lambertian) and by range beyond the sensor's near-field compensation,
// with speckle (multiplicative) and electronic (additive) noise. Nothing here knows the class.
float return_intensity(const RayHit& h, const LidarParams& p, double n_speckle,
                       double n_electronic) {
    const double range_gain = std::clamp(1.0 - h.range_m / p.intensity_falloff_m, 0.2, 1.0);
    const double lambert = std::max(0.05, static_cast<double>(h.cos_incidence));
    const double value =
        h.reflectivity * lambert * range_gain * (1.0 + p.intensity_speckle * n_speckle) +
        p.intensity_noise * n_electronic;
    return static_cast<float>(std::clamp(std::round(value), 0.0, 255.0));
}

// One ray's outcome, in a flat per-sweep buffer (no allocation inside the ray loop).
struct RayResult {
    Eigen::Vector3f xyz;
    float intensity;
    std::uint32_t instance;
    std::uint8_t label;
    bool keep;
};

}  // namespace

PoseAtTime sensor_pose_along(std::vector<Pose2> base_poses, double t0_s, double dt_s,
                             const Isometry3& T_robot_sensor) {
    return [poses = std::move(base_poses), t0_s, dt_s, T_robot_sensor](double t_s) {
        const int steps = static_cast<int>(poses.size()) - 1;
        const double u = std::clamp((t_s - t0_s) / dt_s, 0.0, static_cast<double>(steps));
        const int i = std::min(static_cast<int>(u), steps - 1);
        const Pose2& a = poses[static_cast<std::size_t>(i)];
        const Pose2& b = poses[static_cast<std::size_t>(i) + 1];
        const double alpha = u - i;
        const Pose2 p{a.x_m + alpha * (b.x_m - a.x_m), a.y_m + alpha * (b.y_m - a.y_m),
                      wrap_angle(a.yaw_rad + alpha * angle_diff(b.yaw_rad, a.yaw_rad))};
        return lift_to_3d(p) * T_robot_sensor;
    };
}

const std::vector<double>& vlp32c_elevations_deg() {
    static const std::vector<double> kAngles{
        -25.0, -15.639, -11.31, -8.843, -7.254, -6.148, -5.333, -4.667, -4.0,   -3.667, -3.333,
        -3.0,  -2.667,  -2.333, -2.0,   -1.667, -1.333, -1.0,   -0.667, -0.333, 0.0,    0.333,
        0.667, 1.0,     1.333,  1.667,  2.333,  3.333,  4.667,  7.0,    10.333, 15.0};
    return kAngles;
}

const NameTable<BeamPattern>& beam_patterns_by_name() {
    static const NameTable<BeamPattern> kNames{
        {"vlp16", BeamPattern::kVlp16},
        {"vlp32c", BeamPattern::kVlp32c},
        {"os1_64", BeamPattern::kOs1_64},
        {"os1_128", BeamPattern::kOs1_128},
    };
    return kNames;
}

std::string_view to_string(BeamPattern pattern) {
    return name_in(beam_patterns_by_name(), pattern);
}

std::optional<BeamPattern> parse_beam_pattern(std::string_view name) {
    return value_named(beam_patterns_by_name(), name);
}

const std::vector<double>& beam_elevations_deg(BeamPattern pattern) {
    const auto uniform = [](int beams, double lo, double hi) {
        std::vector<double> e(static_cast<std::size_t>(beams));
        for (int i = 0; i < beams; ++i) e[i] = lo + (hi - lo) * i / (beams - 1);
        return e;
    };
    static const std::vector<double> kVlp16 = uniform(16, -15.0, 15.0);
    static const std::vector<double> kOs1_64 = uniform(64, -22.5, 22.5);
    static const std::vector<double> kOs1_128 = uniform(128, -22.5, 22.5);
    switch (pattern) {
        case BeamPattern::kVlp16:
            return kVlp16;
        case BeamPattern::kOs1_64:
            return kOs1_64;
        case BeamPattern::kOs1_128:
            return kOs1_128;
        case BeamPattern::kVlp32c:
            break;
    }
    return vlp32c_elevations_deg();
}

int LidarParams::num_columns() const {
    return static_cast<int>(std::lround(360.0 / azimuth_step_deg));
}

std::vector<std::string> LidarParams::validate() const { return lidar_table().problems(*this); }

PointCloud simulate_sweep(World& world, const LidarParams& params,
                          const PoseAtTime& T_world_sensor_at, double t_start_s, std::uint64_t seed,
                          std::uint64_t sweep_index, SweepStats* stats) {
    const int columns = params.num_columns();
    const int beams = params.num_beams();
    const double dt_column = params.sweep_duration_s() / columns;
    std::vector<float> cos_el(beams), sin_el(beams);
    for (int b = 0; b < beams; ++b) {
        const double el = deg_to_rad(params.elevations_deg()[b]);
        cos_el[b] = static_cast<float>(std::cos(el));
        sin_el[b] = static_cast<float>(std::sin(el));
    }
    std::vector<RayResult> out(static_cast<std::size_t>(columns) * beams);
    const std::uint64_t stream = seed ^ (sweep_index * 0xA24BAED4963EE407ULL);
    constexpr std::uint64_t kIntensityStream = 0x1A7E5171ULL;

    constexpr int kMaxBeams = 256;  // more than any BeamPattern has
    constexpr int kPacket = World::kPacketSize;
    auto cast_column = [&](int c) {
        const double t_rel = c * dt_column;
        const Isometry3 T_world_sensor = T_world_sensor_at(t_start_s + t_rel);
        const Eigen::Matrix3f R = T_world_sensor.linear().cast<float>();
        const Eigen::Vector3f origin = T_world_sensor.translation().cast<float>();
        const double az = deg_to_rad(c * params.azimuth_step_deg);
        const float ca = static_cast<float>(std::cos(az)), sa = static_cast<float>(std::sin(az));
        std::array<Eigen::Vector3f, kMaxBeams + kPacket> dirs_sensor, dirs_world;
        std::array<RayHit, kMaxBeams + kPacket> hits;
        for (int b = 0; b < beams; ++b) {
            dirs_sensor[b] = Eigen::Vector3f(cos_el[b] * ca, cos_el[b] * sa, sin_el[b]);
            dirs_world[b] = R * dirs_sensor[b];
        }
        const auto max_range = static_cast<float>(params.max_range_m);
        if (params.use_packets) {
            for (int b0 = 0; b0 < beams; b0 += kPacket) {
                bool valid[kPacket];
                for (int i = 0; i < kPacket; ++i) {
                    valid[i] = b0 + i < beams;
                    if (!valid[i]) dirs_world[b0 + i] = Eigen::Vector3f::UnitX();
                }
                world.cast_packet(origin, &dirs_world[b0], max_range, valid, &hits[b0]);
            }
        } else {
            for (int b = 0; b < beams; ++b) hits[b] = world.cast(origin, dirs_world[b], max_range);
        }
        RayResult* o = &out[static_cast<std::size_t>(c) * beams];
        for (int b = 0; b < beams; b += 2) {
            // One normal pair serves two beams; the uniform decides dropout.
            const std::uint64_t ray_id = static_cast<std::uint64_t>(c) * beams + b;
            const auto [n0, n1] = counter_normal_pair(stream, ray_id);
            double m0 = 0.0, m1 = 0.0, e0 = 0.0, e1 = 0.0;
            if (params.intensity) {
                std::tie(m0, m1) = counter_normal_pair(stream ^ kIntensityStream, ray_id);
                std::tie(e0, e1) = counter_normal_pair(stream ^ kIntensityStream, ~ray_id);
            }
            for (int k = 0; k < 2 && b + k < beams; ++k) {
                const RayHit& h = hits[b + k];
                RayResult& r = o[b + k];
                r.keep = false;
                if (!h.hit) continue;
                if (params.dropout > 0.0 && counter_uniform(stream, ~(ray_id + k)) < params.dropout)
                    continue;
                const double range = h.range_m + params.range_noise_m * (k == 0 ? n0 : n1);
                if (range < params.min_range_m || range > params.max_range_m) continue;
                r.keep = true;
                r.xyz = static_cast<float>(range) * dirs_sensor[b + k];
                r.intensity = params.intensity
                                  ? return_intensity(h, params, k == 0 ? m0 : m1, k == 0 ? e0 : e1)
                                  : 0.0f;
                r.label = static_cast<std::uint8_t>(h.label);
                r.instance = h.instance;
            }
        }
    };

    std::unique_ptr<tbb::global_control> limit;
    if (params.num_threads > 1) {
        limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                      static_cast<std::size_t>(params.num_threads));
    }
    world.set_surface_model(params.intensity);
    const int slices = std::min(params.time_slices, columns);
    for (int s = 0; s < slices; ++s) {
        const int c0 = s * columns / slices, c1 = (s + 1) * columns / slices;
        world.set_time(t_start_s + 0.5 * (c0 + c1) * dt_column);
        if (params.num_threads > 1) {
            tbb::parallel_for(tbb::blocked_range<int>(c0, c1, 16),
                              [&](const tbb::blocked_range<int>& r) {
                                  for (int c = r.begin(); c < r.end(); ++c) cast_column(c);
                              });
        } else {
            for (int c = c0; c < c1; ++c) cast_column(c);
        }
    }

    // Gather in firing order (column-major), so output never depends on the thread schedule.
    std::size_t n = 0;
    for (const RayResult& r : out) n += r.keep;
    PointCloud cloud;
    cloud.resize(n, PointFields{.intensity = params.intensity,
                                .ring = true,
                                .time = true,
                                .label = true,
                                .instance = true});
    std::size_t i = 0;
    for (std::size_t k = 0; k < out.size(); ++k) {
        const RayResult& r = out[k];
        if (!r.keep) continue;
        cloud.xyz[i] = r.xyz;
        if (params.intensity) cloud.intensity[i] = r.intensity;
        cloud.ring[i] = static_cast<std::uint16_t>(k % beams);
        cloud.time_s[i] = static_cast<float>(static_cast<double>(k / beams) * dt_column);
        cloud.label[i] = r.label;
        cloud.instance[i] = r.instance;
        ++i;
    }
    if (stats) {
        stats->rays = static_cast<std::size_t>(columns) * beams;
        stats->returns = n;
    }
    return cloud;
}

}  // namespace makeway::sim

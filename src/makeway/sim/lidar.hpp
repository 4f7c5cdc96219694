#pragma once
// A spinning multi-beam LiDAR, by default the Velodyne Ultra Puck (VLP-32C): 32 beams at the
// datasheet's non-uniform elevations (-25 to +15 deg), 360 deg at 0.2 deg steps, 10 Hz. The beam
// layouts of a VLP-16 and of Ouster's OS1-64 and OS1-128 are there too (`lidar.beam_pattern`), so
// the system can be tried with the sensor a user has.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "makeway/common/name_table.hpp"
#include "makeway/common/point_cloud.hpp"
#include "makeway/common/transforms.hpp"
#include "makeway/sim/world.hpp"

namespace makeway::sim {

/// VLP-32C elevation angles [deg], lowest first (ring 0 is the lowest beam).
const std::vector<double>& vlp32c_elevations_deg();

/// Beam layouts from the datasheets: Velodyne VLP-16 (16 beams, -15..+15 deg every 2 deg),
/// VLP-32C (32, -25..+15, denser near the horizon), Ouster OS1-64 and OS1-128 (uniform over
/// -22.5..+22.5 deg).
enum class BeamPattern { kVlp16, kVlp32c, kOs1_64, kOs1_128 };
/// The pattern's elevation angles [deg], lowest first.
const std::vector<double>& beam_elevations_deg(BeamPattern pattern);
/// Every pattern with its name: vlp16, vlp32c, os1_64, os1_128 (as the `lidar.beam_pattern` key
/// and the command line spell them).
const NameTable<BeamPattern>& beam_patterns_by_name();
std::string_view to_string(BeamPattern pattern);
std::optional<BeamPattern> parse_beam_pattern(std::string_view name);

struct LidarParams {
    BeamPattern beam_pattern = BeamPattern::kVlp32c;
    double azimuth_step_deg = 0.2;  ///< 1800 columns per turn
    double rate_hz = 10.0;          ///< turns per second
    double min_range_m = 0.4;
    double max_range_m = 100.0;
    double range_noise_m = 0.015;       ///< Gaussian sigma (datasheet accuracy +-3 cm)
    double dropout = 0.005;             ///< probability that a return is lost
    double intensity_falloff_m = 60.0;  ///< intensity falls linearly to 20 % at this range
    double intensity_speckle = 0.1;     ///< relative sigma of the intensity's multiplicative noise
    double intensity_noise = 2.0;       ///< sigma of the additive intensity noise (0..255 scale)
    int time_slices = 10;               ///< the world is moved this many times per sweep
    int num_threads = 1;                ///< 1: serial; > 1: TBB with this many threads
    bool use_packets = true;            ///< Embree 8-ray packets (false: one ray at a time)
    /// Each return's intensity, with its noise. false: the sweep has no intensity channel, and the
    /// surface model and two of the three noise draws per return are skipped (World's surface
    /// model is set to match), for runs where nothing reads it; positions, dropout, ranges, labels
    /// are the same either way.
    bool intensity = true;

    std::vector<std::string> validate() const;
    int num_columns() const;
    const std::vector<double>& elevations_deg() const { return beam_elevations_deg(beam_pattern); }
    int num_beams() const { return static_cast<int>(elevations_deg().size()); }
    double sweep_duration_s() const { return 1.0 / rate_hz; }
};

/// Sensor pose at an absolute time [s] (T_world_sensor).
using PoseAtTime = std::function<Isometry3(double t_s)>;

/// The sensor's pose through a stretch of driving: the robot's base at `base_poses[i]` at time
/// t0_s + i dt_s, linear in between (yaw along the shorter turn), held at the ends; the sensor
/// mounted at T_robot_sensor. Needs at least two poses.
PoseAtTime sensor_pose_along(std::vector<Pose2> base_poses, double t0_s, double dt_s,
                             const Isometry3& T_robot_sensor);

struct SweepStats {
    std::size_t rays = 0;
    std::size_t returns = 0;
};

/// One full turn starting at t_start_s. Points are in the sensor frame of their own firing time
/// (uncorrected, as a real sensor gives them), with ring, time since t_start_s, label and
/// instance. The world is moved to the middle of each time slice. `seed` and `sweep_index` make
/// noise and dropout reproducible, identical for any thread count.
PointCloud simulate_sweep(World& world, const LidarParams& params,
                          const PoseAtTime& T_world_sensor_at, double t_start_s, std::uint64_t seed,
                          std::uint64_t sweep_index, SweepStats* stats = nullptr);

}  // namespace makeway::sim

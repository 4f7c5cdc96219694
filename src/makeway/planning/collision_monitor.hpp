#pragma once
// The collision monitor: the last check between the navigator and the motors, on the raw sensor
// data, independent of the costmap and the planner (nav2's collision_monitor is the model: a stop
// zone, a slowdown zone, an approach check, min_points, min_height/max_height; its parameter
// names where they fit).
//
// Every zone is the robot's true footprint (a rectangle), grown by a padding and swept along the
// commanded arc, on the latest de-skewed sweep's returns that the body can hit (between its ground
// clearance and its top), plus the earlier returns the sensor can no longer see. A LiDAR
// `sensor_height_m` up whose lowest beam points `lowest_beam_deg` down sees a part at height z only
// from (sensor_height_m - z) / tan(-lowest_beam_deg) away (a VLP-32C 0.45 m up: 0.92 m for a part
// 2 cm above the floor): a chair leg the robot closes in on vanishes from its sweeps. So a return
// is remembered (up to blind_memory_s) while it lies closer to the sensor than both that radius
// and where it was seen from; once the sensor could see its place again, only the new sweep counts
// (a walker that has moved on leaves no trail).
//
// Along the arc, u is the time the commanded (v, w) would take to get there ("command seconds").
// Scaling the command by s in (0, 1] keeps the arc and travels it at rate s; stopping from there
// takes u_brake(s) = s * latency_s + s^2 * k / 2 with k = max(|v| / a_v, |w| / a_w) (both axes
// brake at their acceleration limits). So:
//   stop     : min_points returns in the footprint + stop_padding_m swept over u in
//              [0, u_brake(1)] (latency plus braking distance at the commanded speed) -> v = w = 0.
//   slowdown : returns in the footprint + slowdown_padding_m swept over
//              u in [0, u_brake(1) + slowdown_time_s] -> (v, w) *= slowdown_ratio.
//   approach : the first u_c at which the footprint + stop_padding_m touches returns; the command
//              is slowed so that contact stays at least time_before_collision_s away:
//              s = u_c / time_before_collision_s (nav2's approach polygon).
// A return counts only where the motion brings the footprint closer to it than it is now, so a
// robot standing next to a wall may always drive or turn away from it.
//
// Recovery: when the monitor has held the robot (stop, or approach below min_scale) for
// recovery_after_s, it backs up (straight, backup_distance_m at backup_speed_mps) if the sweep
// shows that space free, else turns on the spot (rotate_angle_rad, the free side first); the
// recovery's own command passes the same stop check every cycle.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "makeway/common/point_cloud.hpp"
#include "makeway/common/robot_body.hpp"
#include "makeway/common/transforms.hpp"
#include "makeway/common/velocity_command.hpp"

namespace makeway::planning {

struct CollisionMonitorParams {
    bool enabled = true;
    double footprint_length_m = 0.508;  ///< the robot's true footprint (a rectangle on the base)
    double footprint_width_m = 0.430;
    BodyHeights body;                   ///< returns outside [ground_clearance_m, top_m] are ignored (nav2 min/max_height)
    double max_acc_mps2 = 1.0;          ///< braking deceleration, linear
    double max_ang_acc_radps2 = 3.0;    ///< braking deceleration, angular
    double latency_s = 0.2;             ///< sweep age + one control period before a command acts
    int min_points = 2;                 ///< returns in a zone before it acts (nav2 min_points)
    double stop_padding_m = 0.04;       ///< the stop zone and the approach check: footprint grown by this
    double slowdown_padding_m = 0.15;   ///< the slowdown zone: footprint grown by this ...
    double slowdown_time_s = 0.6;       ///< ... swept this far past the braking arc [command s]
    double slowdown_ratio = 0.5;        ///< the command's share inside the slowdown zone
    double time_before_collision_s = 1.2;  ///< approach: contact kept at least this far ahead [s]; 0: off
    double simulation_time_step_s = 0.05;  ///< approach and zones: the step along the arc [command s]
    double min_scale = 0.05;            ///< an approach scale below this holds the robot (counts as a stop)
    double sensor_height_m = 0.45;      ///< the LiDAR above the floor (on the base's centre) ...
    double lowest_beam_deg = -25.0;     ///< ... and its lowest beam: what it cannot see near it is remembered ...
    double blind_memory_s = 3.0;        ///< ... at most this long
    double max_range_m = 4.0;           ///< returns farther than this from the base are not looked at
    double recovery_after_s = 3.0;      ///< held this long: start a recovery
    double backup_speed_mps = 0.15;
    double backup_distance_m = 0.3;
    double rotate_speed_radps = 0.8;
    double rotate_angle_rad = 1.2;
    std::vector<std::string> validate() const;
};

/// Why the monitor changed the command this cycle (run.json's stop_reason).
enum class MonitorAction { kNone, kSlowdown, kApproach, kStop, kBackup, kRotate, kBlocked };
std::string_view to_string(MonitorAction action);
inline constexpr int kMonitorActions = 7;

struct MonitorInput {
    double t_s = 0.0;
    Pose2 pose;                                ///< the base in the world frame of the points (estimated)
    const PointCloud* points_world = nullptr;  ///< the latest de-skewed sweep; null: only the memory
    VelocityCommand command;                   ///< what the navigator asks for
};

struct MonitorResult {
    VelocityCommand command;  ///< what goes to the motors
    MonitorAction action = MonitorAction::kNone;
    double scale = 1.0;       ///< the command's share that passed (0: held)
    bool recovering = false;
    bool started_recovery = false;
};

class CollisionMonitor {
public:
    /// Throws std::invalid_argument listing every problem of `params`.
    explicit CollisionMonitor(const CollisionMonitorParams& params);

    MonitorResult filter(const MonitorInput& input);
    /// The check alone, on returns already in the base frame (x forward, y left): no memory, no
    /// recovery. What filter() does per cycle, exposed for tests and tools.
    MonitorResult check(const VelocityCommand& command, const std::vector<Eigen::Vector2d>& points_base) const;
    const CollisionMonitorParams& params() const { return params_; }

private:
    struct Remembered {
        Eigen::Vector2d p_world;
        double t_s;
        double blind_m;  ///< remembered while closer than this to the sensor
    };
    /// The first u in [0, u_max] (steps of simulation_time_step_s) where the padded footprint
    /// swept along (v, w) holds min_points returns it is closing in on; a negative value: none.
    double first_contact(double v, double w, double padding, double u_max, const std::vector<Eigen::Vector2d>& pts) const;
    bool recovery_free(const VelocityCommand& c, double duration_s, const std::vector<Eigen::Vector2d>& pts) const;

    CollisionMonitorParams params_;
    std::vector<Remembered> memory_;
    double held_since_ = -1.0;     ///< when the current hold began (-1: not held)
    double recovery_until_ = -1.0;
    VelocityCommand recovery_command_;
};

}  // namespace makeway::planning

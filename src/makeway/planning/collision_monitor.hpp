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
// and where it was seen from; once the sensor could see its place again, only the new sweep counts.
// New returns (below) are not remembered there: a walker that has moved on leaves no trail.
// Memory cannot follow what moves inside that blind ring (a chair a person pulls toward a turning
// robot: its seat is seen, its base is not), nor what is too low to be seen more than once (a
// round table's 3 cm foot): the footprints the caller hands in stand in for returns there, their
// outlines sampled where the sensor cannot see the floor (nav2's polygon source). The Controller
// hands in, with object_footprints, the boxes of the object map's chairs that moved lately, and
// with object_parts, the body-height parts of every object a CAD model placed (its foot, its
// star base, its legs: verification::part_outlines).
//
// Each zone follows the robot's own motion model (the simulator's and DWA's): from the current
// velocity, each axis moves toward its target within the acceleration limits. With a_v, a_w the
// limits and L = latency_s (the sweep's age and one control period, during which the command
// runs before the next check can change it):
//   stop     : the command for L, then braking to a standstill: min_points returns in the
//              footprint + stop_padding_m anywhere along it -> v = w = 0 (braking is the least
//              motion left; standing still always passes).
//   slowdown : the command for L + slowdown_time_s, then braking, with the footprint +
//              slowdown_padding_m -> at most slowdown_ratio of the top speeds (a cap, not a
//              factor on the command: DWA samples around the current velocity, so a factor would
//              compound cycle after cycle down to a crawl).
//   approach : the command for time_before_collision_s; first contact of the footprint +
//              stop_padding_m at t_c -> the command scaled by t_c / time_before_collision_s, so
//              that contact stays that far ahead (nav2's approach polygon).
// A return counts only where the motion brings the footprint closer to it than it is now, so a
// robot standing next to a wall may always drive or turn away from it.
//
// People: a return in a cell (or next to one) that held returns in fewer than dynamic_min_seen
// of the last dynamic_history sweeps, and at least dynamic_min_height_m up, is new, maybe moving
// (a surface coming out of another's shadow is new for one sweep; near the floor the lowest
// rings' noise is new every sweep). A surface that stays is seen sweep after sweep; a walker who
// turns back toward the robot walks over the cells it left, each seen in one earlier sweep, so
// with dynamic_min_seen 2 it stays new (off by default: pulled chairs become movers too, README).
// dynamic_min_seen_off_chairs asks that only away from the chairs the robot knows of
// (MonitorInput::chairs_world), where a pulled chair's and a flickering thin part's returns are
// not. A robot without an object map (chairs_world null) cannot tell them from a walker's: there
// it stays dynamic_min_seen (with 2 everywhere, oppo lost a run and gained a robot-caused
// contact on 200 scenes, README).
// For the stop zone and the approach check a new return's padding grows by dynamic_speed_mps for
// every second until the robot would be there (latency included). So the robot stops for a
// walker who could step into its way before it has braked, and waits while the walker is near
// its path; a walker standing still is an obstacle like any other (its returns are not new).
// With dynamic_personal_space_m, a new return that close to the footprint holds the robot whatever
// the command (a robot creeping or turning beside a walker meets the walker's next step), unless
// it lies beside a chair the robot knows of (a pulled chair's returns are new too, and a robot
// held by every pulled chair beside it gives up). Off by default (README).
// Within dynamic_turn_space_m (0.3 m; 0: off) of a new return not beside a known chair, the turn
// rate is capped at dynamic_turn_max_radps: a turning robot's corners sweep sideways at w times
// their reach, into a walker beside it even while the robot drives away from the walker (one
// overtaking the rear corner of a robot that turns off the walker's line), which the zones, made
// for what the robot closes in on, pass.
// With dynamic_memory_s, a walker near the robot (dynamic_memory_range_m; a body's worth of new
// returns, not beside a known chair) is remembered that long as a mover, its padding grown by its
// age too (a walker last seen 0.5 s ago may be 0.5 m from there), until new returns are seen
// within that reach of it (the walker, seen again). A walker who turns back toward the robot
// walks into cells it left, not new, and one who steps inside the sensor's minimum range is not
// seen at all: either way the robot does not move off toward where it was last seen moving. Off
// by default: ours, whose object map knows a pulled chair late, loses runs to it (README).
// Returns seen in one sweep only are not remembered (the floor's noise); with low_edge_support a
// low one is, when it is an arc of returns (a table's foot, in the lowest ring's reach about one
// sweep). Off by default: on 200 scenes oppo won 2 runs with it and ours lost 2 (README).
// With dynamic_cluster_m, a mover stays a mover for dynamic_history sweeps: returns within about
// that of a cell with dynamic_cluster_min_new new returns move too (a walker who turns back walks
// into the cells it just left, which are not new). Off by default: chairs people push become
// movers too, and the robot waits for them (README).
//
// Gaps: a surface seen edge-on returns nothing (a chair's seat at the sensor's height, between
// the two posts of its back, which do return): a robot turning beside the chair sweeps a corner
// into the gap between the posts. Between two still returns at most bridge_gap_m apart (and 3 cm
// less than the footprint's width: nothing the robot fits through) with no return around the
// middle, the segment counts as returns (gap_bridge.hpp). A robot already beside such a segment may
// still move away from it, like from any return.
//
// Recovery: when the monitor has held the robot (stop, or approach below min_scale) for
// recovery_after_s, it backs up (straight, backup_distance_m at backup_speed_mps) if the sweep
// shows that space free, else turns on the spot (rotate_angle_rad, the free side first); the
// recovery's own command passes the same stop check every cycle.
//
// Give way (give_way_horizon_s > 0; 1 s by default, README): a chair someone pulls out comes at
// 0.1-0.2 m/s into whatever stands behind it, and a robot the stop zone holds beside it waits to
// be hit (the zones forbid moving toward returns, not being moved into). With the moving objects
// the caller knows of (MonitorInput::movers_world, each carried along its velocity: the
// Controller's MovingChairs, which carries the object map's boxes from when they were measured
// to now), when even a robot that stops now would come within
// give_way_margin_m of one over the horizon, and the decided command would too, the command is
// replaced by the candidate that keeps the most clearance (the decided command, straight back or
// straight on at half and at full give_way_speed_mps), as the stop check lets it through
// (give_way.hpp). The way off holds until a standing robot would be clear (the navigator's next
// command turns back into the chair's way as soon as it looks clear for the horizon), unless the
// navigator's command keeps more. A command that drives at a mover while standing would be clear
// is the zones' business: a robot that waited for every chair moving ahead of it would not arrive.
#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "makeway/common/point_cloud.hpp"
#include "makeway/common/polygon2d.hpp"
#include "makeway/common/robot_body.hpp"
#include "makeway/common/robot_description.hpp"
#include "makeway/common/transforms.hpp"
#include "makeway/common/velocity_command.hpp"
#include "makeway/planning/give_way.hpp"

namespace makeway::planning {

struct CollisionMonitorParams {
    bool enabled = true;
    double footprint_length_m = 0.508;  ///< the robot's true footprint (a rectangle on the base)
    double footprint_width_m = 0.430;
    BodyHeights
        body;  ///< returns outside [ground_clearance_m, top_m] are ignored (nav2 min/max_height)
    double max_v_mps = 0.75;  ///< the robot's top speeds (the slowdown zone caps a share of them)
    double max_w_radps = 2.0;
    double max_acc_mps2 = 1.0;        ///< braking deceleration, linear
    double max_ang_acc_radps2 = 3.0;  ///< braking deceleration, angular
    double latency_s = 0.2;           ///< sweep age + one control period before a command acts
    int min_points = 2;               ///< returns in a zone before it acts (nav2 min_points)
    double stop_padding_m =
        0.04;  ///< the stop zone and the approach check: footprint grown by this
    double slowdown_padding_m = 0.1;  ///< the slowdown zone: footprint grown by this ...
    double slowdown_time_s = 0.3;     ///< ... along the command this much longer before braking [s]
    double slowdown_ratio =
        0.6;  ///< inside the slowdown zone: at most this share of the top speeds
    double time_before_collision_s =
        0.8;  ///< approach: contact kept at least this far ahead [s]; 0: off
    double simulation_time_step_s = 0.05;  ///< the zones' time step along the predicted motion [s]
    double dynamic_speed_mps =
        1.0;                   ///< new returns may move this fast (a walking person); 0: all static
    int dynamic_history = 5;   ///< sweeps a cell is remembered as seen ...
    int dynamic_min_seen = 1;  ///< ... new: seen in fewer than this many of them (2: a walker
                               ///< turning back is new; README)
    int dynamic_min_seen_off_chairs =
        0;  ///< away from known chairs (personal_space_object_margin_m), this many instead when
            ///< larger (2: a walker turning back is new, a pulled chair is not); 0: off
    double dynamic_cluster_m = 0.0;  ///< returns within about this of a mover (this sweep or the
                                     ///< last dynamic_history) move too; 0: off ...
    int dynamic_cluster_min_new =
        5;  ///< ... a mover: a cell of that size with this many new returns
    double dynamic_min_height_m =
        0.1;  ///< lower returns are never new (floor noise at the lowest rings' reach)
    double dynamic_memory_s = 0.0;  ///< a mover is remembered this long, its padding growing with
                                    ///< its age, until seen again; 0: off
    double dynamic_memory_range_m =
        0.8;  ///< ... movers this close to the base (farther, the next sweeps see them again) ...
    int dynamic_memory_min_new =
        5;  ///< ... with this many new returns within 0.2 m (a body, not a sliver out of a shadow)
    double dynamic_personal_space_m = 0.0;  ///< a new return this close to the footprint holds the
                                            ///< robot (any command); 0: off (README) ...
    double personal_space_object_margin_m =
        0.2;  ///< ... unless it lies this close to a known chair (MonitorInput::chairs_world): the
              ///< chair moves, not a walker
    double dynamic_turn_space_m = 0.3;  ///< a new return this close to the footprint (not beside a
                                        ///< known chair) caps the turn rate ...; 0: off (README)
    double dynamic_turn_max_radps =
        0.12;                 ///< ... at this (the Jackal's corners, 0.33 m out, sweep at 0.04 m/s)
    double min_scale = 0.05;  ///< an approach scale below this holds the robot (counts as a stop)
    double sensor_height_m = 0.45;  ///< the LiDAR above the floor (on the base's centre) ...
    double lowest_beam_deg =
        -25.0;  ///< ... and its lowest beam: what it cannot see near it is remembered ...
    double blind_memory_s =
        10.0;  ///< ... at most this long (a robot held in front of a chair leg keeps it)
    int low_edge_support =
        0;  ///< a return below dynamic_min_height_m seen in one sweep only is remembered with this
            ///< many returns around it (5 x 5 cells); 0: never
    bool object_footprints =
        true;  ///< the Controller hands in (MonitorInput::footprints_world) the boxes of chairs ...
    double object_moving_mps = 0.05;  ///< ... that moved faster than this in the last
                                      ///< blind_memory_s
    double object_lead_s = 0.0;  ///< ... each swept along its velocity this far ahead (the map lags
                                 ///< a keyframe); 0: where it is
    bool object_parts = true;    ///< the Controller hands in the body-height parts of the objects
                                 ///< their CAD models placed (kept blind_memory_s after the map
                                 ///< drops one)
    double bridge_gap_m = 0.35;  ///< a gap this narrow between two still returns is solid (the
                                 ///< seat between a chair back's posts); 0: off. At most the
                                 ///< footprint's width - 3 cm: no gap the robot fits through closes
    double max_range_m = 4.0;    ///< returns farther than this from the base are not looked at
    double recovery_after_s = 3.0;  ///< held this long: start a recovery
    double backup_speed_mps = 0.15;
    double backup_distance_m = 0.3;
    double rotate_speed_radps = 0.8;
    double rotate_angle_rad = 1.2;
    double give_way_horizon_s =
        1.0;  ///< give way: a known moving object would come this soon [s] ... 0: off
    double give_way_margin_m = 0.05;  ///< ... within this of a standing robot's footprint ...
    double give_way_speed_mps = 0.5;  ///< ... moves the robot off, straight back or on at this
                                      ///< speed or half of it, or holds it
    double give_way_min_speed_mps =
        0.08;  ///< objects moving at least this fast are given way to (the Controller's: ...
    double give_way_window_s =
        1.0;  ///< ... the object map's velocity, else its box's displacement over this long)
    double give_way_lag_s = 0.3;  ///< a moving chair's box was measured this long before the
                                  ///< cycle it changed in (carried along its velocity to now)
    std::vector<std::string> validate() const;
    /// The robot's footprint, body, top speeds and accelerations (the sensor's height and lowest
    /// beam are its mounting's and stay as they are).
    void apply_robot(const RobotDescription& robot);
};

/// Why the monitor changed the command this cycle (run.json's stop_reason).
enum class MonitorAction {
    kNone,
    kSlowdown,
    kApproach,
    kStop,
    kBackup,
    kRotate,
    kBlocked,
    kGiveWay
};
std::string_view to_string(MonitorAction action);
inline constexpr int kMonitorActions = 8;

struct MonitorInput {
    double t_s = 0.0;
    Pose2 pose;  ///< the base in the world frame of the points (estimated)
    const PointCloud* points_world =
        nullptr;                        ///< the latest de-skewed sweep; null: only the memory
    VelocityCommand command;            ///< what the navigator asks for
    double v_mps = 0.0, w_radps = 0.0;  ///< the base's velocity now (wheel odometry)
    /// Objects solid below the body's top (null or empty: none): where the sensor cannot see the
    /// floor, their outlines count as returns (the Controller's: object_footprints, object_parts).
    const std::vector<Polygon2>* footprints_world = nullptr;
    /// Every chair the robot knows of (null: the robot has no object map): a new return beside
    /// one is the chair being pulled, which the personal space leaves to the stop zone (a
    /// walker's is not beside one).
    const std::vector<Polygon2>* chairs_world = nullptr;
    /// Objects the robot knows are moving, with their velocities (null: none): give way to them.
    const std::vector<MovingOutline>* movers_world = nullptr;
};

struct MonitorResult {
    VelocityCommand command;  ///< what goes to the motors
    MonitorAction action = MonitorAction::kNone;
    double scale = 1.0;  ///< the command's share that passed (0: held)
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
    /// `dynamic` (empty, or one flag per point): returns that are new in this sweep (1), or new and
    /// beside a known chair (2: moving, but no walker: out of the personal space); `current`: the
    /// velocity now (the first form: already at the commanded velocity).
    MonitorResult check(const VelocityCommand& command,
                        const std::vector<Eigen::Vector2d>& points_base,
                        const std::vector<char>& dynamic = {}) const;
    /// `age_s` (empty, or one per point): how long ago a flagged return was seen (remembered
    /// movers); its padding grows by dynamic_speed_mps over that age too.
    MonitorResult check(const VelocityCommand& command, const VelocityCommand& current,
                        const std::vector<Eigen::Vector2d>& points_base,
                        const std::vector<char>& dynamic = {},
                        const std::vector<double>& age_s = {}) const;
    const CollisionMonitorParams& params() const { return params_; }

  private:
    struct Remembered {
        Eigen::Vector2d p_world;
        double t_s;
        double blind_m;  ///< remembered while closer than this to the sensor
    };
    /// A motion: from `current`, `command` for command_s, then (brake) to a standstill.
    struct Motion {
        VelocityCommand current, command;
        double command_s = 0.0;
        bool brake = true;
    };
    /// The base's poses along a motion (time, pose in the base frame at time 0), every
    /// simulation_time_step_s.
    std::vector<std::pair<double, Pose2>> trajectory(const Motion& m) const;
    /// The first time along `m` at which the footprint grown by `padding` holds min_points returns
    /// it is closing in on; negative: none. A flagged (`dynamic`) return's padding grows by
    /// dynamic_speed_mps (age + latency_s + t).
    double first_contact(const Motion& m, double padding, const std::vector<Eigen::Vector2d>& pts,
                         const std::vector<char>& dynamic = {},
                         const std::vector<double>& age_s = {}) const;
    /// Half the footprint's length and width (the rectangle centred on the base).
    Eigen::Vector2d footprint_half() const {
        return {0.5 * params_.footprint_length_m, 0.5 * params_.footprint_width_m};
    }
    /// How far from the sensor a part z_m above the floor drops out of its lowest beam.
    double blind_radius_m(double z_m) const;
    /// filter()'s decision on the command (recovering, held, recovery started), before giving way.
    MonitorResult decide(const MonitorInput& in, const VelocityCommand& current,
                         const std::vector<Eigen::Vector2d>& pts, const std::vector<char>& dynamic,
                         const std::vector<double>& age_s);
    /// `r` replaced by the candidate that keeps the most clearance from in.movers_world, when a
    /// standing robot and r's command would both come within give_way_margin_m of one over
    /// give_way_horizon_s (or the way off chosen before still keeps more).
    void give_way(const MonitorInput& in, const VelocityCommand& current,
                  const std::vector<Eigen::Vector2d>& pts, const std::vector<char>& dynamic,
                  const std::vector<double>& age_s, MonitorResult& r);
    bool recovery_free(const VelocityCommand& c, const VelocityCommand& current, double duration_s,
                       const std::vector<Eigen::Vector2d>& pts, const std::vector<char>& dynamic,
                       const std::vector<double>& age_s) const;

    CollisionMonitorParams params_;
    double tan_down_;  ///< tan of the lowest beam's angle below the horizon
    std::vector<Remembered> memory_;
    std::vector<std::pair<Eigen::Vector2d, double>>
        movers_;  ///< remembered movers (world, when seen), dynamic_memory_s
    std::deque<std::vector<std::int64_t>>
        previous_cells_;  ///< the last sweeps' thinned cells (each sorted), for new returns
    std::deque<std::vector<std::int64_t>>
        previous_movers_;       ///< the last sweeps' coarse cells of new returns (each sorted)
    double held_since_ = -1.0;  ///< when the current hold began (-1: not held)
    double recovery_until_ = -1.0;
    VelocityCommand recovery_command_;
    std::optional<VelocityCommand> giving_way_;  ///< the way off while giving way
};

}  // namespace makeway::planning

#pragma once
// The ROS node's engine: the online system (pipeline::OnlineSystem, the same assembly as the
// benchmark's `ours` and `makeway run`) on a worker thread behind a queue, so that the sweep
// callback only converts and enqueues and a slow keyframe never drops a sweep. Goals come in from
// any thread and are checked and applied at the next sweep; every sweep yields the guarded command
// (navigator, then collision monitor), the plan and a status. send_command_at() is what the node
// sends at its control rate: the last command while the sweeps and the odometry are fresh, else
// zero. It names no ROS type and is C++17-clean: the node's main (ros/makeway_node.cpp) is C++17
// because ROS 1's message headers are.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "makeway/common/costmap.hpp"
#include "makeway/common/object_estimate.hpp"
#include "makeway/common/transforms.hpp"
#include "makeway/common/velocity_command.hpp"
#include "makeway/costmap/affordance.hpp"
#include "ros/bag_io.hpp"

namespace makeway::rosio {

struct NodeSettings {
    std::string config;  ///< YAML, the program's format (empty: built-in defaults)
    std::string model;   ///< detector weights (empty: models/detector.pt)
    std::string cad;     ///< CAD folder (empty: verification skipped)
    std::string map;     ///< map_server YAML (empty: a free square around the start)
    std::string zones;   ///< learned zones (makeway learn-zones; empty: the hand-drawn ones)
    double costmap_size_m = 40.0;
    std::optional<Pose2>
        start;  ///< the base at the first sweep (default: the first odometry pose, else 0 0 0)
    std::optional<Isometry3>
        T_base_sensor;                ///< measured extrinsics (default: the configuration's robot)
    double sensor_timeout_s = 0.3;    ///< no sweep ended this recently: zero velocity
    double odometry_timeout_s = 0.3;  ///< no odometry this recent: zero velocity
    /// true: the keyframe chain (detection, verification, tracking) runs on its own thread and
    /// each sweep's command waits only for the pose and the costmap (the object map it sees is
    /// the last finished one); false: every sweep waits for its keyframe's perception.
    bool async_perception = false;
    /// With async perception, the keyframe chain's share of the computer: its thread's nice value
    /// (0: the control path's priority; higher: it yields the cores to the control path, which on
    /// a small computer is what keeps a sweep's command within its latency) and how many threads
    /// its verification and network may use (0: every core but one, at least one).
    int perception_nice = 10;
    int perception_threads = 0;
    std::function<double()> clock;  ///< the node's time [s] (ROS time: sim time under
                                    ///< use_sim_time); empty: the sweep's end
    /// Sends a command to the motors. Called under the engine's lock by every path that commands
    /// (a sweep's output, send_command_at(), cancel()), so a cancel is never overtaken by a
    /// command computed before it. Must not block or call the engine.
    std::function<void(const VelocityCommand&)> send_command;
    double odometry_wait_s = 0.2;  ///< how long a sweep waits for odometry covering its end
    std::size_t max_queue = 600;   ///< sweeps waiting beyond this are dropped (and counted)
};

/// Where the navigation stands (published as JSON on ~status).
struct NavStatus {
    std::string state = "idle";     ///< idle, driving, reached, blocked, stopped
    std::string why;                ///< for blocked and stopped (and a refused goal: "goal ...")
    double distance_left_m = -1.0;  ///< along the plan (straight without one); -1: no goal
    std::optional<Eigen::Vector2d> goal;
};
std::string to_json(const NavStatus& status);

/// What the node sends at `now_s`: `last` while the newest sweep ended within sensor_timeout_s
/// and the newest odometry is within odometry_timeout_s, else zero with the reason.
struct GatedCommand {
    VelocityCommand command;
    std::string why;  ///< empty: passed
};
GatedCommand gate_command(const VelocityCommand& last, std::optional<double> last_sweep_end_s,
                          std::optional<double> last_odometry_s, double now_s,
                          double sensor_timeout_s, double odometry_timeout_s);

/// What one sweep produced, carrying the stamp of the data it used (the sweep's end).
struct NodeOutput {
    double stamp_s = 0.0;
    Pose2 pose;  ///< the base, estimated
    std::optional<Pose2>
        wheel_pose;  ///< the wheel odometry's pose of the base at the sweep's end (its odom frame)
    Isometry3 T_world_sensor = Isometry3::Identity();
    bool keyframe = false;  ///< this sweep formed a keyframe (the costmap is published on these)
    bool perception =
        false;  ///< async perception finished a keyframe: only objects and object_map_json are set
    std::vector<ObjectEstimate> objects;  ///< the object map
    const Costmap* costmap = nullptr;  ///< valid during the callback (null on perception outputs)
    std::string object_map_json;  ///< a finished keyframe: the object map as `makeway run` writes
                                  ///< it (else empty)
    double per_sweep_ms = 0.0, keyframe_ms = 0.0, queue_wait_ms = 0.0;
    double front_end_ms = 0.0;   ///< the sweep's pose and de-skewing (LiDAR odometry)
    double navigation_ms = 0.0;  ///< costmap update, planning, DWA and the collision monitor
    double latency_ms = 0.0;     ///< from the sweep's arrival (push_sweep) to this output
    VelocityCommand command;     ///< the guarded command from this sweep (zero when idle)
    GatedCommand gated;  ///< what to send now: `command` through gate_command at settings.clock()
    std::vector<Eigen::Vector2d> plan;  ///< the global plan, world frame (empty when idle)
    NavStatus status;
    std::string notice;  ///< a check of the first sweep changed a setting: one line to log (else
                         ///< empty)
};

struct NodeStats {
    std::size_t received = 0, processed = 0, dropped = 0, keyframes = 0, max_queue = 0;
};

class NodeEngine {
  public:
    using Publish = std::function<void(const NodeOutput&)>;
    /// Loads everything (throws io::FileError naming a bad file) and starts the worker, which
    /// calls `publish` after every sweep.
    NodeEngine(const NodeSettings& settings, Publish publish);
    ~NodeEngine();  ///< finishes the queued sweeps, then stops
    NodeEngine(const NodeEngine&) = delete;
    NodeEngine& operator=(const NodeEngine&) = delete;

    /// From the callbacks' threads; return at once.
    void push_sweep(CloudSweep sweep);
    void push_odometry(const StampedPose2& pose);
    /// A goal (world frame), from any thread: checked at the next sweep (finite, inside the map,
    /// not inside an obstacle); a refused goal leaves the robot still, the status says why.
    void set_goal(const Eigen::Vector2d& goal_m);
    /// Stops at once (sends zero; send_command_at() gives zero from now) and drops the goal at the
    /// next sweep.
    void cancel();
    /// What to send to the motors at `now_s` (gate_command on the last sweep's command), sent
    /// (settings.send_command) under the engine's lock; the node's control rate.
    GatedCommand send_command_at(double now_s);
    /// Blocks until every queued sweep is processed (and its keyframes perceived).
    void drain();

    NodeStats stats() const;
    const costmap::AffordanceParams& zones() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace makeway::rosio

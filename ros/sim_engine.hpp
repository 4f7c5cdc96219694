#pragma once
// The simulator as a robot, for the ROS sim node (ros/sim_node.cpp): the scene's Jackal driven by
// velocity commands, its VLP-32C sweeps with per-point time, its drifting wheel odometry, and a
// judge that watches every contact and writes the run's report. What leaves it toward the robot's
// software is only what the drivers of a real robot publish (sweeps in the sensor frame, wheel
// odometry); the truth (pose, contacts) goes to the report and the ground-truth topics apart.
// Names no ROS type (C++20 inside, C++17-clean header).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "makeway/common/point_cloud.hpp"
#include "makeway/common/transforms.hpp"
#include "makeway/common/velocity_command.hpp"

namespace makeway::rosio {

struct SimRobotSettings {
    std::string scene;  ///< scene YAML (required)
    std::string
        config;  ///< the program's configuration (lidar, robot, odometry noise); empty: defaults
    std::uint64_t seed = 0;          ///< sensor noise and odometry drift
    double command_timeout_s = 0.5;  ///< no command this long: the robot brakes to a stop
    int lidar_threads = 1;
};

/// One sweep period of the simulated robot.
struct SimTick {
    double t_start_s = 0.0, t_end_s = 0.0;
    PointCloud sweep;  ///< sensor frame; per-point time since t_start_s
    struct Odometry {
        double stamp_s;
        Pose2 pose;  ///< wheel odometry (drifting), its own frame
        double v_mps, w_radps;
    };
    std::vector<Odometry>
        odometry;  ///< one per physics step (t_start_s excluded, t_end_s included)
    Pose2 truth;   ///< the base at t_end_s (ground truth: report and /ground_truth only)
    double v_mps = 0.0, w_radps = 0.0;  ///< truth
};

class SimRobot {
  public:
    /// Loads the scene and the configuration; throws io::FileError naming a bad file.
    explicit SimRobot(const SimRobotSettings& settings);
    ~SimRobot();
    SimRobot(const SimRobot&) = delete;
    SimRobot& operator=(const SimRobot&) = delete;

    /// A velocity command received at t_s (sim time).
    void command(const VelocityCommand& c, double t_s);
    /// Drives one sweep period on the latest command (zero once it is older than the timeout),
    /// judging every physics step, and sweeps the LiDAR over it.
    SimTick tick();

    double period_s() const;
    Pose2 start() const;
    Isometry3 T_base_sensor() const;
    /// Writes the CAD models of the room's furniture (each distinct model of the scene once, as
    /// `chair_NAME.obj` / `table_NAME.obj`: io/cad_folder.hpp's layout) into `folder`, which
    /// appears whole (written beside it, then renamed). What a robot's user has: the room's CAD
    /// models, not where they stand.
    void write_cad_folder(const std::string& folder) const;
    /// The scene's legs: its waypoint, then its goal (world frame).
    std::vector<Eigen::Vector2d> route() const;
    /// The run so far as JSON: time, distance, the driven path, every contact (walls, furniture,
    /// people; robot- or other-caused), risk time (the robot's centre inside a true object's
    /// affordance zone, as the benchmark scores it) and the distance left to the scene's goal.
    /// `extra`: more JSON members to merge (the mission's outcome), as a JSON object text.
    std::string report_json(const std::string& extra = "{}") const;
    /// Whether the robot has touched walls or furniture (the benchmark's collision).
    bool collided() const;
    int robot_caused_contacts() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace makeway::rosio

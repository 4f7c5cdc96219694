#pragma once
// Records a drive through a scene: the robot follows a route (pure pursuit on the diff-drive model)
// while the LiDAR sweeps; each frame carries the sweep, the true sensor pose, the wheel odometry
// and every object's ground truth.
#include <vector>

#include "makeway/sim/lidar.hpp"
#include "makeway/sim/robot.hpp"
#include "makeway/sim/world.hpp"

namespace makeway::sim {

struct SequenceParams {
    LidarParams lidar;
    RobotParams robot;
    OdometryNoiseParams odometry;
    std::uint64_t seed = 0;
    double physics_rate_hz = 100.0;
    double lookahead_m = 0.4;  ///< pure-pursuit lookahead
    double goal_tolerance_m = 0.15;

    std::vector<std::string> validate() const;
};

struct SimFrame {
    int index = 0;
    double stamp_s = 0.0;                   ///< sweep start
    PointCloud points_sensor;               ///< raw sweep (see simulate_sweep)
    Isometry3 T_world_sensor;               ///< true sensor pose at stamp_s
    Pose2 true_pose;                        ///< robot base at stamp_s
    Pose2 odometry_pose;                    ///< wheel odometry of the base at stamp_s
    Pose2 odometry_end_pose;                ///< wheel odometry of the base at the sweep's end
    std::vector<ObjectState> objects;       ///< ground truth at stamp_s
    std::vector<Eigen::Vector2d> people_m;  ///< walker positions at stamp_s
    bool collided = false;                  ///< the footprint touched something during the sweep
    SweepStats sweep;
};

class SequenceSimulator {
  public:
    /// `route` runs from the scene's start (e.g. mission_route()); the robot starts at scene.start.
    SequenceSimulator(const Scene& scene, std::vector<Eigen::Vector2d> route,
                      const SequenceParams& params);

    /// Simulates the next sweep period and returns its frame.
    SimFrame next();
    bool reached_goal() const { return reached_goal_; }
    const std::vector<Pose2>& trajectory() const { return trajectory_; }
    const World& world() const { return world_; }
    /// Where the robot starts: the scene's start, turned to face the route (what a robot is told).
    const Pose2& start_pose() const { return start_pose_; }

  private:
    VelocityCommand pure_pursuit(const RobotState& state);

    const Scene& scene_;
    std::vector<Eigen::Vector2d> route_;
    SequenceParams params_;
    World world_;
    CollisionChecker checker_;
    RobotState state_;
    Pose2 start_pose_;
    WheelOdometry odometry_;
    std::size_t route_index_ = 0;
    int frame_index_ = 0;
    bool reached_goal_ = false;
    std::vector<Pose2> trajectory_;
};

}  // namespace makeway::sim

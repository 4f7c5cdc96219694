#pragma once
// The navigation half of the online system: the layered costmap (static map of walls, LiDAR
// obstacles, object affordance zones, inflation), A* on it, DWA to follow the plan, and the policy
// around them (replan when due, keeping the current plan unless the new one is clearly cheaper,
// or when the plan is blocked; turn on the spot when DWA finds no safe velocity; back up when
// stuck). One `step` per sweep, on the robot's own pose estimate.
#include <cstddef>
#include <vector>

#include "makeway/common/costmap.hpp"
#include "makeway/common/object_estimate.hpp"
#include "makeway/common/point_cloud.hpp"
#include "makeway/common/transforms.hpp"
#include "makeway/common/velocity_command.hpp"
#include "makeway/pipeline/object_costmap.hpp"
#include "makeway/pipeline/system_params.hpp"
#include "makeway/planning/astar.hpp"

namespace makeway::pipeline {

struct NavigatorInput {
    double t_s = 0.0;
    Pose2 pose;                         ///< the base, estimated
    double v_mps = 0.0, w_radps = 0.0;  ///< current velocity (the commanded one, or wheel odometry)
    const PointCloud* points_world = nullptr;  ///< the latest sweep, world frame (may be null)
    Eigen::Vector3d sensor_world_m = Eigen::Vector3d::Zero();
    std::vector<ObjectEstimate> objects;  ///< the object map (empty for the classic costmap)
};

struct NavigatorStep {
    VelocityCommand command;
    bool replanned = false;
    bool kept_plan = false;  ///< A* planned anew, but the plan being followed was not much dearer
    planning::PlanStatus plan_status = planning::PlanStatus::kOk;  ///< of the last A* call
    bool has_plan = false;                                         ///< a plan to follow this cycle
    bool dwa_found = true;    ///< false: every velocity collided, turning on the spot
    bool recovering = false;  ///< backing up
    bool started_recovery = false;
    bool detour = false;  ///< the recovery also marked the stuck spot for A* to go around
    bool reached_waypoint = false;
    bool arrived = false;  ///< the last leg's goal is reached (by the pose estimate)
    bool gave_up =
        false;  ///< no plan, or no progress despite recoveries, for give_up_s: the mission failed
    double update_ms = 0.0;  ///< costmap update + planning + DWA
};

/// What the navigator did this cycle, in one word (run.json's nav_state): arrived, gave_up,
/// backing_up (a stuck recovery), no_plan (A* found none yet, standing), turning (DWA found no
/// safe velocity, turning on the spot toward the plan), following (DWA along the plan).
const char* to_string_state(const NavigatorStep& step);

class Navigator {
  public:
    /// `static_map`: the prebuilt map of walls (its geometry becomes the costmap's). Throws
    /// std::invalid_argument listing every problem of `params`.
    Navigator(const Costmap& static_map, const NavigatorParams& params);

    /// The legs to drive (waypoints, then the goal); empty: none (step() keeps the costmap and
    /// reports arrived). A new route restarts the progress and give-up clocks.
    void set_route(std::vector<Eigen::Vector2d> legs_m);
    NavigatorStep step(const NavigatorInput& input);

    const Costmap& costmap() const { return costmap_.master(); }
    const std::vector<Eigen::Vector2d>& plan() const { return plan_; }
    std::size_t leg() const { return leg_; }
    bool arrived() const { return leg_ >= legs_.size(); }
    /// The way left to the current leg's target from `robot_m`: along the plan from its point
    /// nearest the robot, straight without a plan; 0 when arrived.
    double remaining_m(const Eigen::Vector2d& robot_m) const;

  private:
    bool plan_blocked(const Eigen::Vector2d& robot_m) const;
    /// A* to the leg's target; `around`: the plan goes around the stuck spots (not through them).
    /// With `kept_cost` (and a plan being followed): it and `new_cost` get the objective of the
    /// rest of that plan (from `from_m`) and of the new plan, on the map A* searched (infinite:
    /// the rest enters a cell A* may not).
    planning::PlanResult plan(const Eigen::Vector2d& from_m, double t_s, bool& around,
                              double* kept_cost = nullptr, double* new_cost = nullptr);
    std::size_t nearest_plan_index(const Eigen::Vector2d& robot_m) const;  ///< 0 for an empty plan
    Eigen::Vector2d along_plan(const Eigen::Vector2d& robot_m, double ahead_m) const;
    VelocityCommand follow_plan(const NavigatorInput& input, NavigatorStep& step) const;
    /// Whether turning on the spot by turn_clear_rad toward `sign` (+1: left) keeps the bare
    /// footprint off lethal cells it is not on now.
    bool turn_clear(const Pose2& pose, double sign) const;
    void check_progress(const NavigatorInput& input, NavigatorStep& step);
    void start_recovery(const NavigatorInput& input,
                        NavigatorStep& step);  ///< back up, then replan (around the spot ahead)

    NavigatorParams params_;
    ObjectCostmap costmap_;
    std::vector<Eigen::Vector2d> legs_;
    std::size_t leg_ = 0;
    std::vector<Eigen::Vector2d> plan_;
    double last_plan_t_ = -1e9;
    double best_remaining_m_ = 0.0;  ///< the shortest way left seen on this leg
    std::size_t progress_leg_ = 0;
    double progress_t_ = 0.0, recovery_until_ = -1.0;
    double moved_t_ =
        0.0;  ///< when the robot last made progress along its plan (recoveries do not reset it)
    double planned_t_ = 0.0;  ///< when A* last found a plan
    bool started_ = false;
    struct Avoided {
        Eigen::Vector2d at_m;
        double until_s;
    };
    std::vector<Avoided>
        avoided_;      ///< where the robot got stuck: A* goes around them while they last
    int detours_ = 0;  ///< on this leg
    double standstill_since_ =
        -1.0;  ///< DWA's best velocity has been a standstill since (-1: it is not)
    bool detour_pending_ =
        false;  ///< the leg's first detour was decided; its first plan restarts the progress clock
};

}  // namespace makeway::pipeline

#pragma once
// Local planning: the Dynamic Window Approach (Fox, Burgard, Thrun 1997). Velocities reachable
// within one control period (the dynamic window) are sampled; each is rolled out for a horizon
// with the robot's rectangular footprint; velocities whose rollout collides, or that could not
// stop before the first collision, are inadmissible; the rest are scored by path alignment, goal
// heading, clearance (costmap cost) and speed, each normalised over the samples.
//
// The plan's cost envelope: A* routes around affordance zones at a price, and a carrot 1.2 m
// ahead lets DWA cut the corners the plan went around. With `plan_envelope`, a rollout is charged
// the cost it takes above the highest cost the plan itself accepts between the robot and the
// carrot (plus `envelope_margin`); only the rollouts with the least such excess are scored. A zone
// the plan crosses (the only way, or the goal inside it) stays open to DWA; one it avoids does too
// when no other velocity is admissible.
#include <string>
#include <vector>

#include "makeway/common/costmap.hpp"
#include "makeway/common/transforms.hpp"
#include "makeway/common/velocity_command.hpp"

namespace makeway::planning {

struct DwaParams {
    double max_v_mps = 0.75;
    double min_v_mps = 0.0;
    double max_w_radps = 2.0;
    double acc_v_mps2 = 1.0;
    double acc_w_radps2 = 3.0;
    double control_dt_s = 0.1;
    double horizon_s = 1.6;
    double rollout_dt_s = 0.1;
    int v_samples = 7;
    int w_samples = 15;
    double footprint_length_m = 0.508;
    double footprint_width_m = 0.430;
    double footprint_padding_m =
        0.0;  ///< rollouts keep this clear of lethal cells (the collision monitor's stop padding)
    double lookahead_m = 1.2;  ///< carrot distance along the global path
    double w_path = 1.0;
    double w_heading = 0.6;
    double w_clearance = 0.5;
    double w_speed = 0.4;
    bool plan_envelope = true;
    double envelope_margin =
        10.0;  ///< cost units above the plan's highest cost still inside the envelope
    std::vector<std::string> validate() const;
};

struct DwaState {
    Pose2 pose;
    double v_mps = 0.0;
    double w_radps = 0.0;
};

struct DwaResult {
    bool found = false;  ///< false: every sampled velocity collides (recovery needed)
    VelocityCommand command;
    int admissible = 0;
    int samples = 0;
    std::vector<Pose2> best_rollout;
};

/// Whether the footprint at `pose` touches a lethal cell (cells outside the map count as lethal).
/// The footprint (with its padding) is sampled at half the costmap's resolution.
bool footprint_collides(const Costmap& costmap, const Pose2& pose, const DwaParams& params);

/// footprint_collides for many poses near one place (a DWA step's rollouts), with the same answers.
/// A summed-area table counts the lethal cells of `window`; a pose whose footprint's bounding box
/// lies in the window and holds no lethal cell is free without sampling its ~500 points, which in
/// a room is most poses of most rollouts. Poses near lethal cells, or outside the window or the
/// map, are sampled as footprint_collides does. Keeps a reference to `costmap`.
class FootprintChecker {
  public:
    FootprintChecker(const Costmap& costmap, const DwaParams& params, const GridWindow& window);
    bool collides(const Pose2& pose) const;

  private:
    const Costmap& map_;
    std::vector<Eigen::Vector2d> samples_;
    double half_length_m_ = 0.0, half_width_m_ = 0.0;
    GridWindow window_;            ///< clipped to the map
    std::vector<int> lethal_sum_;  ///< (w+1) x (h+1): lethal cells in [x0, x0+i) x [y0, y0+j)
};

/// `path_m` is the global path (any length >= 1); the carrot is taken along it from the point
/// nearest the robot.
DwaResult dwa_step(const Costmap& costmap, const DwaState& state,
                   const std::vector<Eigen::Vector2d>& path_m, const DwaParams& params);

}  // namespace makeway::planning

#pragma once
// Who touched what: the one judge of contacts for the benchmark (eval/navigation.cpp) and the
// simulator as a ROS robot (ros/sim_engine.cpp), so a run over ROS is judged as a run in process.
// A contact is counted when it starts, per kind of thing (walls, furniture, people), and it is the
// robot's doing when the body moved toward it faster than `robot_caused_mps` (robot_caused_contact
// in sim/robot.hpp); else a walker or a pushed chair came into a stopped or receding robot.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "makeway/sim/robot.hpp"

namespace makeway::sim {

/// One contact, when it started.
struct ContactEvent {
    double t_s = 0.0;
    std::string kind;  ///< walls, furniture or people
    bool robot_caused = false;
    double toward_mps = 0.0;  ///< the body's speed toward what it touched
    Eigen::Vector2d where_m = Eigen::Vector2d::Zero();
};

/// Contacts with one kind of thing, split by who caused them.
struct ContactCounts {
    int robot_caused = 0;  ///< the robot was moving toward what it touched
    int other_caused = 0;  ///< a walker or a pushed chair came into a stopped or receding robot
    int total() const { return robot_caused + other_caused; }
};

class ContactJudge {
  public:
    /// Keeps a reference to `checker`.
    ContactJudge(const CollisionChecker& checker, const RobotParams& robot,
                 double robot_caused_mps = 0.05);
    /// The robot at t_s: the contacts that start now (one per kind at most; usually none).
    std::vector<ContactEvent> step(const RobotState& state, double t_s);
    /// The same, for a caller that already checked whether the footprint touches anything at t_s
    /// (the benchmark's scorer counts collisions and person contacts apart): no check repeated.
    std::vector<ContactEvent> step(const RobotState& state, double t_s, bool touching_anything);

  private:
    const CollisionChecker& checker_;
    double length_m_, width_m_, robot_caused_mps_;
    bool touching_[3] = {false, false, false};  // walls, furniture, people
};

}  // namespace makeway::sim

#pragma once
// The simulated robot: a Clearpath Jackal (differential drive) with a LiDAR on top, its wheel
// odometry (with drift), and footprint collision checks against everything in the scene.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "makeway/common/random.hpp"
#include "makeway/common/robot_body.hpp"
#include "makeway/common/robot_description.hpp"
#include "makeway/common/transforms.hpp"
#include "makeway/common/velocity_command.hpp"
#include "makeway/sim/scene.hpp"
#include "makeway/sim/scene_dynamics.hpp"

namespace makeway::sim {

/// The robot the simulator drives is the robot the system is told it has
/// (common/robot_description.hpp).
using RobotParams = RobotDescription;

struct RobotState {
    Pose2 pose;
    double v_mps = 0.0;
    double w_radps = 0.0;
};

/// Advances the unicycle model by dt_s: the command is clamped to the velocity limits, then the
/// velocities move toward it within the acceleration limits, and the pose follows the exact arc.
RobotState step_diff_drive(const RobotState& state, const VelocityCommand& command, double dt_s,
                           const RobotParams& params);

/// The body's speed toward a contact at `contact_world` [m/s]: the velocity of the body at the
/// contact point (rigid body: v along the heading plus w x r) along the outward normal of the
/// footprint side nearest the contact.
double speed_toward_contact(const Pose2& pose, double v_mps, double w_radps,
                            const Eigen::Vector2d& contact_world, double length_m, double width_m);

/// Whether a contact at `contact_world` was the robot's doing: the velocity of the body at the
/// contact point (rigid body: v along the heading plus w x r) has a component of more than
/// `threshold_mps` along the outward normal of the footprint side nearest the contact.
bool robot_caused_contact(const Pose2& pose, double v_mps, double w_radps,
                          const Eigen::Vector2d& contact_world, double length_m, double width_m,
                          double threshold_mps = 0.05);

/// Wheel odometry drift: noise on each increment, proportional to the motion.
struct OdometryNoiseParams {
    double translation_noise_per_m =
        0.02;  ///< distance error sigma after 1 m [m]; grows with sqrt(distance)
    double heading_noise_per_rad =
        0.03;  ///< heading error sigma after turning 1 rad [rad]; grows with sqrt
    double heading_noise_per_m =
        0.01;  ///< heading drift sigma after 1 m [rad]; grows with sqrt(distance)
    std::vector<std::string> validate() const;
};

class WheelOdometry {
  public:
    WheelOdometry(const Pose2& start, const OdometryNoiseParams& params, std::uint64_t seed);
    /// Integrates the motion between two true poses, with noise.
    void update(const Pose2& true_before, const Pose2& true_after);
    const Pose2& pose() const { return pose_; }

  private:
    Pose2 pose_;
    OdometryNoiseParams params_;
    Rng rng_;
};

/// Surface samples of the mesh parts the body can hit (between its ground clearance and its top),
/// projected to the floor, thinned on a grid of spacing_m / 2: a footprint check's points, and a
/// static map's obstacles from an environment mesh.
std::vector<Eigen::Vector2d> low_surface_points(const TriangleMesh& mesh, const BodyHeights& body,
                                                double spacing_m);

/// Footprint collision checks against walls, pillars, environment meshes, furniture (the parts of
/// its mesh below the robot's top) and people, at any time of the scene.
class CollisionChecker {
  public:
    CollisionChecker(const Scene& scene, const std::vector<ObjectModel>& models,
                     const RobotParams& robot, double spacing_m = 0.02);

    /// What a check looks at.
    enum class Against { kEverything, kStructureAndFurniture, kPeople, kStructure, kFurniture };
    /// Whether the footprint at `pose` overlaps anything (of `against`) at t_s.
    bool collides(const Pose2& pose, double t_s, Against against = Against::kEverything) const;
    /// Where the footprint at `pose` overlaps something (of `against`) at t_s: the mean of the
    /// obstacle points inside it, world frame; nothing when it overlaps nothing.
    std::optional<Eigen::Vector2d> contact_point(const Pose2& pose, double t_s,
                                                 Against against) const;
    /// Distance from the footprint to the nearest obstacle at t_s [m], capped at max_m.
    double clearance_m(const Pose2& pose, double t_s, double max_m = 5.0) const;
    /// Every obstacle point at t_s, floor plane [m] (for rasterising).
    std::vector<Eigen::Vector2d> obstacle_points(double t_s) const;

  private:
    template <typename Fn>
    void for_each_point_near(const Eigen::Vector2d& centre, double radius, double t_s, Fn&& fn,
                             Against against = Against::kEverything) const;

    const Scene& scene_;
    RobotParams robot_;
    std::vector<Eigen::Vector2d> static_points_;
    std::vector<std::vector<Eigen::Vector2d>> object_points_;  ///< object frame
    std::vector<double> object_radius_m_;
};

}  // namespace makeway::sim

#pragma once
// Ground-truth navigability: an occupancy grid of the scene at one time, grown by the robot's
// circumscribed radius (so any heading fits), and the shortest 8-connected route through it.
// Used to accept generated scenes and to drive the simulated robot on `--route auto`.
#include <optional>
#include <vector>

#include "makeway/sim/robot.hpp"

namespace makeway::sim {

struct NavGrid {
    Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();  ///< corner of cell (0, 0)
    double resolution_m = 0.05;
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> blocked;  ///< row-major, 1 = the robot centre cannot be here

    bool inside(int ix, int iy) const { return ix >= 0 && iy >= 0 && ix < width && iy < height; }
    bool is_blocked(int ix, int iy) const {
        return !inside(ix, iy) || blocked[iy * width + ix] != 0;
    }
    Eigen::Vector2i cell_of(const Eigen::Vector2d& p_m) const;
    Eigen::Vector2d centre_of(int ix, int iy) const;
};

/// Obstacles at t_s grown by inflation_m (default: the robot's circumscribed radius + 5 cm).
NavGrid make_nav_grid(const Scene& scene, const CollisionChecker& checker, const RobotParams& robot,
                      double t_s = 0.0, double resolution_m = 0.05, double inflation_m = -1.0);

/// Shortest route between two points (A*, 8-connected), shortened by line-of-sight; nullopt when
/// either end is blocked or no route exists.
std::optional<std::vector<Eigen::Vector2d>> find_route(const NavGrid& grid,
                                                       const Eigen::Vector2d& from_m,
                                                       const Eigen::Vector2d& to_m);

/// start -> waypoint -> goal, or nullopt.
std::optional<std::vector<Eigen::Vector2d>> mission_route(const Scene& scene, const NavGrid& grid);

/// The route the simulated robot drives on `--route auto`: the mission route with the widest
/// clearance margin that still connects (margins of 0.30, 0.20, 0.10, 0.05 m beyond the
/// circumscribed radius are tried), so that a path follower cutting corners stays clear.
std::optional<std::vector<Eigen::Vector2d>> drive_route(const Scene& scene,
                                                        const CollisionChecker& checker,
                                                        const RobotParams& robot);

/// Length of a polyline [m].
double route_length_m(const std::vector<Eigen::Vector2d>& route);

}  // namespace makeway::sim

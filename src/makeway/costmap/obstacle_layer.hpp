#pragma once
// Obstacles seen by the LiDAR: cells holding a return the robot's body can hit (between its ground
// clearance and its top, common/robot_body.hpp) are marked lethal; every ray (to returns below the
// top, ground included) clears the cells it crosses, but a low mark only where the ray passes no
// higher than it (a ray over a floor runner proves nothing about the runner). Marks persist until
// a ray clears them, so objects that moved leave no stale cost.
//
// Low returns (below low_band_top_m) are where floor noise lives: they mark only within
// low_mark_range_m of the sensor (a pose estimate tilted by a tenth of a degree lifts the floor
// 1 cm at 6 m) and only when at least low_min_returns of them, and low_min_share of the cell's
// returns below the low band's top, stand above the clearance in one sweep: range noise lifts a
// few floor returns of a cell (sigma 6 mm at the lowest ring), a runner or a foot plate most.
// A ray clears a low mark only where it passes at most low_clear_margin_m above the mark's top: a
// round table's 3 cm foot is reached by the lowest ring about 0.9 m out, and from closer the rays
// to the floor behind it pass 2-5 cm over it, which proves nothing about it (with a 5 cm margin
// they cleared it, and the robot's corner swept over the foot). That holds for a low mark with
// another beside it (a plate's edge is an arc of cells); one alone is what floor noise or a pose
// error raises once at the lowest ring's reach, and a robot driving at it would never see its cell
// again (inside the blind ring), so rays within low_single_clear_margin_m (5 cm) clear it. A low
// mark is also cleared by a sweep that shows its cell bare: low_min_returns returns below the
// clearance there, none above (a mark that floor noise or a pose error raised is seen bare as the
// robot drives on; a plate's top keeps returning above the clearance).
#include <cstdint>
#include <memory>
#include <vector>

#include "makeway/common/robot_body.hpp"
#include "makeway/costmap/layer.hpp"

namespace makeway::costmap {

struct ObstacleLayerParams {
    BodyHeights body;  ///< what the robot can hit: returns outside are floor or overhead
    double low_band_top_m = 0.05;  ///< returns below this are "low" (see above)
    double low_mark_range_m = 2.5;
    int low_min_returns = 2;
    double low_min_share = 0.5;
    double low_clear_margin_m = 0.01;  ///< a ray clears a low mark with another beside it passing
                                       ///< at most this far above its top (see above) ...
    double low_single_clear_margin_m =
        0.05;  ///< ... one alone (floor noise, a pose error), this far
    double mark_range_m = 6.0;
    double clear_range_m = 8.0;
    int threads = 2;  ///< threads walking the rays (1: the caller's alone); the same map for any
    std::vector<std::string> validate() const;
};

class ObstacleLayer : public Layer {
  public:
    ObstacleLayer(const Costmap& geometry, const ObstacleLayerParams& params);
    std::string name() const override { return "obstacle"; }
    void update_bounds(const Costmap& master, const LayerInput& input, GridWindow& window) override;
    void update_costs(Costmap& master, const GridWindow& window) override;
    const Costmap& grid() const { return grid_; }

  private:
    struct Scratch {                // per cell, during one update (zero between updates)
        float end_z = 0.0f;         ///< its lowest return [m]
        float low_top = 0.0f;       ///< the highest low return [m]
        std::uint16_t low = 0;      ///< low returns the body can hit
        std::uint16_t floor = 0;    ///< returns below the clearance, or too far
        std::uint16_t bare = 0;     ///< returns below the clearance within low_mark_range_m
        std::uint8_t endpoint = 0;  ///< 0 none, 1 clear-only, 2 mark
    };
    static constexpr int kBlock =
        16;  ///< rays cross blocks of kBlock x kBlock cells holding no mark in one step

    ObstacleLayerParams params_;
    Costmap grid_;
    std::vector<Scratch> scratch_;  ///< one per cell, one cache line per return
    std::vector<float> top_;        ///< per marked cell: the highest return behind its mark [m]
    std::vector<std::uint8_t> grouped_;  ///< per low mark: another one beside it when marked
    struct Return {           // a return within clear_range_m, in the grid, below the body's top
        int cell;             ///< its cell's index
        std::uint32_t point;  ///< its index in the sweep
        double d2;            ///< its squared horizontal distance from the sensor [m^2]
    };
    std::vector<Return> returns_;             ///< this update's, in scan order
    std::vector<int> cells_;                  ///< the cells with an endpoint in this update
    std::vector<std::uint16_t> block_marks_;  ///< per block: its cells that are not free in grid_
    struct Threads;                           ///< threads > 1: the rays' TBB arena
    std::shared_ptr<Threads> threads_;        ///< shared by copies (an arena is not copyable)
};

}  // namespace makeway::costmap

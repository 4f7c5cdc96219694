#pragma once
// The object affordance layer: each object's class-specific zone (affordance.hpp), aligned with its
// pose. The update window covers the zones that changed (an object that appeared, vanished, moved
// or changed class or size: its old zone and its new one), so zones left behind are cleared and
// zones that stand are not rewritten every sweep.
#include <cstdint>
#include <limits>
#include <vector>

#include "makeway/costmap/affordance.hpp"
#include "makeway/costmap/layer.hpp"

namespace makeway::costmap {

class AffordanceLayer : public Layer {
  public:
    explicit AffordanceLayer(const AffordanceParams& params) : params_(params) {}
    std::string name() const override { return "affordance"; }
    void update_bounds(const Costmap& master, const LayerInput& input, GridWindow& window) override;
    void update_costs(Costmap& master, const GridWindow& window) override;

  private:
    /// The master's cells of an object's zone and its margin.
    GridWindow zone_window(const Costmap& master, const ObjectEstimate& o) const;
    /// An object's zone as the master's cells hold it: its costs over the zone's window, computed
    /// when the zone first overlaps an update and copied from then on (a zone depends on the
    /// object alone; rewriting it cell by cell, a rotation and a square root per cell, every time
    /// the obstacles changed a window beside it was a tenth of a truth-fed run).
    struct Patch {
        GridWindow window;               ///< the zone's cells in the master (clipped to it)
        std::vector<std::uint8_t> cost;  ///< row-major over window; empty: not computed yet
    };
    AffordanceParams params_;
    std::vector<ObjectEstimate>
        objects_;  ///< the kept objects (existence >= min_existence) of the last update
    std::vector<Patch> patches_;  ///< one per object in objects_
    Eigen::Vector2d patch_origin_m_ = Eigen::Vector2d::Constant(
        std::numeric_limits<double>::quiet_NaN());  ///< the master's geometry the patches are of
    double patch_resolution_m_ = 0.0;
};

}  // namespace makeway::costmap

#pragma once
// Inflation around lethal cells, with nav2's formula: cost 253 within the inscribed radius, then
// 252 * exp(-k (d - r_inscribed)) out to the inflation radius. Distances are exact Euclidean
// (Felzenszwalb-Huttenlocher distance transform over the window).
#include <memory>

#include "makeway/costmap/layer.hpp"

namespace makeway::costmap {

struct InflationParams {
    double inscribed_radius_m = 0.215;  ///< half the Jackal's width
    double inflation_radius_m = 0.55;
    double cost_scaling = 3.0;  ///< k [1/m]
    int threads = 1;            ///< the distance transform's threads (the same costs for any count)
    std::vector<std::string> validate() const;
};

/// The cost at distance d_m from the nearest lethal cell.
std::uint8_t inflation_cost(double d_m, const InflationParams& params);

class InflationLayer : public Layer {
  public:
    explicit InflationLayer(const InflationParams& params);
    std::string name() const override { return "inflation"; }
    void update_bounds(const Costmap& master, const LayerInput& input, GridWindow& window) override;
    void update_costs(Costmap& master, const GridWindow& window) override;

  private:
    InflationParams params_;
    double table_resolution_m_ = 0.0;  ///< the resolution cost_of_d2_ was made for
    std::vector<std::uint8_t>
        cost_of_d2_;  ///< inflation_cost at sqrt(k) cells, out to the first free k past the radius
    struct Threads;   ///< params_.threads > 1: the distance transform's TBB arena
    std::shared_ptr<Threads> threads_;
};

/// Exact squared Euclidean distance [cells^2] from every cell of `window` to the nearest cell with
/// cost >= kLethal inside `source` (a window containing it). Row-major over `window`.
std::vector<double> squared_distance_to_lethal(const Costmap& grid, const GridWindow& source,
                                               const GridWindow& window);

}  // namespace makeway::costmap

#pragma once
// Class-specific affordance zones (the paper's object-aware costmaps). Defined once here and used
// both by the costmap layer and by the benchmark's risk metric, so every method is scored against
// the same zones.
//
// Chair: an ellipse centred on the chair, elongated along its forward/backward axis, because chairs
// are slid backwards and forwards: semi-axes l/2 + forward_back_m (along x) and w/2 + side_m.
// Table: the table's rectangle padded by sides_m on its long sides, where people sit, and by ends_m
// at the ends (nobody sits there); a near-square table (round ones) is padded by sides_m all round.
// Cost: `peak_cost` on the object, falling linearly in the zone coordinate u (0 on the object's
// footprint, 1 on the zone boundary) to `edge_cost`; 0 outside. All costs are soft (<= 252), so a
// zone steers the robot but never closes a passage.
//
// Margin (`margin_m` > 0): outside a zone, within margin_m of its boundary, the cost falls linearly
// from `margin_cost` to 1. Without it A* rides a zone's boundary on its cost-0 cells and the robot,
// a few centimetres off its plan, is inside the zone; DWA, kept to the plan's costs, then
// refuses every rollout that clips the zone and creeps. The margin is costmap only: the zone (risk
// time, in_affordance_zone) stays where it is. A learned zone that learned anything (no metric
// boundary) gets none.
//
// With `learned` set (learned_zone.hpp, `makeway learn-zones`), a class with a learned zone gets
// the density of where its footprint went in this building instead, blended with the shape above by
// the amount of evidence; every function below follows it.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "makeway/common/costmap.hpp"
#include "makeway/common/object_estimate.hpp"
#include "makeway/costmap/learned_zone.hpp"

namespace makeway::costmap {

struct ChairZoneParams {
    double forward_back_m = 0.6;  ///< reach beyond the chair along its axis, both ways
    double side_m = 0.15;         ///< reach beyond the chair sideways
    double peak_cost = 220;       ///< on the chair
    double edge_cost = 40;        ///< at the zone boundary
};

struct TableZoneParams {
    double sides_m = 0.75;             ///< padding on the sitting (long) sides
    double ends_m = 0.15;              ///< padding at the ends
    double square_tolerance_m = 0.15;  ///< |length - width| below this: padded on all sides
    double peak_cost = 200;
    double edge_cost = 30;
};

struct AffordanceParams {
    ChairZoneParams chair;
    TableZoneParams table;
    double min_existence = 0.5;  ///< objects less likely than this get no zone
    /// Outside a zone, within this of its boundary, the margin's cost (0: no margin; README,
    /// Table II's twenty-first pass) ...
    double margin_m = 0.15;
    double margin_cost = 20.0;  ///< ... falling from this at the boundary to 1
    /// Learned zones (a zones file); null, or a class without one: the hand-drawn zone.
    std::shared_ptr<const LearnedZones> learned;
    std::vector<std::string> validate() const;
};

/// Zone coordinate of p for the object: 0 on the footprint, 1 on the boundary, > 1 outside.
double zone_coordinate(const ObjectEstimate& object, const AffordanceParams& params,
                       const Eigen::Vector2d& p_m);

/// Whether p lies inside the object's zone (u <= 1): the risk-zone definition.
inline bool in_affordance_zone(const ObjectEstimate& object, const AffordanceParams& params,
                               const Eigen::Vector2d& p_m) {
    return zone_coordinate(object, params, p_m) <= 1.0;
}

/// The soft cost at p (0 outside the zone and its margin).
std::uint8_t zone_cost(const ObjectEstimate& object, const AffordanceParams& params,
                       const Eigen::Vector2d& p_m);

/// The zone's boundary (u = 1) as a closed polygon of `rays` points, traced outward from the
/// object's centre in 1 cm steps (up to 6 m): for pictures and markers.
std::vector<Eigen::Vector2d> zone_outline(const ObjectEstimate& object,
                                          const AffordanceParams& params, int rays = 72);

/// Axis-aligned world bounds of the zone [m] (its margin not included).
void zone_bounds(const ObjectEstimate& object, const AffordanceParams& params,
                 Eigen::Vector2d& min_m, Eigen::Vector2d& max_m);

}  // namespace makeway::costmap

#include "makeway/costmap/param_tables.hpp"

namespace makeway::costmap {

const ParamTable<AffordanceParams>& affordance_table() {
    using A = AffordanceParams;
    static const ParamTable<A> table = [] {
        ParamTable<ChairZoneParams> chair;
        chair
            .add("forward_back_m", &ChairZoneParams::forward_back_m, closed(0.0, 5.0),
                 "an ellipse along the chair's axis: reach beyond the chair, both ways")
            .add("side_m", &ChairZoneParams::side_m, closed(0.0, 5.0),
                 "reach beyond the chair sideways")
            .add("peak_cost", &ChairZoneParams::peak_cost, closed(0.0, 252.0),
                 "on the chair; soft costs are 1..252")
            .add("edge_cost", &ChairZoneParams::edge_cost, closed(0.0, 252.0),
                 "at the zone boundary")
            .require([](const ChairZoneParams& c) { return c.edge_cost <= c.peak_cost; },
                     "edge_cost must be at most peak_cost");
        ParamTable<TableZoneParams> tab;
        tab.add("sides_m", &TableZoneParams::sides_m, closed(0.0, 5.0),
                "a rectangle padded on the long (sitting) sides by this ...")
            .add("ends_m", &TableZoneParams::ends_m, closed(0.0, 5.0),
                 "... and at the ends by this")
            .add("square_tolerance_m", &TableZoneParams::square_tolerance_m, closed(0.0, 5.0),
                 "|length - width| below this: padded all round")
            .add("peak_cost", &TableZoneParams::peak_cost, closed(0.0, 252.0), "on the table")
            .add("edge_cost", &TableZoneParams::edge_cost, closed(0.0, 252.0),
                 "at the zone boundary")
            .require([](const TableZoneParams& t) { return t.edge_cost <= t.peak_cost; },
                     "edge_cost must be at most peak_cost");
        ParamTable<A> t;
        t.add("min_existence", &A::min_existence, closed(0.0, 1.0),
              "objects less likely than this get no zone")
            .add("margin_m", &A::margin_m, closed(0.0, 2.0),
                 "outside a zone, within this of its boundary, a margin the plan keeps off (0: "
                 "none; the risk zone is unchanged) ...")
            .add("margin_cost", &A::margin_cost, closed(1.0, 252.0),
                 "... its cost at the zone's boundary, falling to 1 at margin_m")
            .include(
                "chair.", [](A& a) -> ChairZoneParams& { return a.chair; }, chair)
            .include(
                "table.", [](A& a) -> TableZoneParams& { return a.table; }, tab);
        return t;
    }();
    return table;
}

const ParamTable<LearnedZones>& learned_zones_table() {
    using L = LearnedZones;
    static const ParamTable<L> table = [] {
        ParamTable<L> t;
        t.add("kernel_m", &L::kernel_m, above(0.0, 0.2),
              "s: the footprint's edges are smoothed by a Gaussian of this width")
            .add("coverage_threshold", &L::coverage_threshold, open(0.0, 1.0),
                 "the zone: where the footprint goes at least this often")
            .add("prior_strength", &L::prior_strength, closed(0.0, 1e6),
                 "n0: pseudo-observations of the hand-drawn zone blended in");
        return t;
    }();
    return table;
}

const ParamTable<InflationParams>& inflation_table() {
    static const ParamTable<InflationParams> table = [] {
        ParamTable<InflationParams> t;
        t.add("cost_scaling", &InflationParams::cost_scaling, open(0.0, 100.0),
              "k [1/m]: costs decay as exp(-k (d - inscribed))");
        return t;
    }();
    return table;
}

const ParamTable<ObstacleLayerParams>& obstacle_layer_table() {
    using O = ObstacleLayerParams;
    static const ParamTable<O> table = [] {
        ParamTable<O> t;
        t.add("low_mark_range_m", &O::low_mark_range_m, closed(0.0, 100.0),
              "returns below 5 cm mark only this close (a tilted pose estimate lifts the far "
              "floor) ...")
            .renamed_from("low_obstacle_range_m")
            .add("low_min_returns", &O::low_min_returns, closed(1, 65535),
                 "... and only when this many fall in a cell ...")
            .renamed_from("low_obstacle_min_returns")
            .add("low_min_share", &O::low_min_share, closed(0.0, 1.0),
                 "... and this share of the cell's low returns stand above the clearance (floor "
                 "noise lifts a few)")
            .renamed_from("low_obstacle_min_share")
            .add("low_clear_margin_m", &O::low_clear_margin_m, closed(0.0, 1.0),
                 "a ray clears a low mark with another beside it only passing at most this far "
                 "above its top (rays over a table's foot prove nothing about it) ...")
            .add("low_single_clear_margin_m", &O::low_single_clear_margin_m, closed(0.0, 1.0),
                 "... a low mark alone (floor noise at the lowest ring's reach), this far")
            .add("mark_range_m", &O::mark_range_m, above(0.0, 100.0), "returns farther do not mark")
            .add("clear_range_m", &O::clear_range_m, above(0.0, 100.0),
                 "rays clear free space this far")
            .add("threads", &O::threads, closed(1, 256),
                 "threads walking the rays and (the object costmap's) inflating: the same map for "
                 "any count")
            .require([](const O& o) { return o.mark_range_m <= o.clear_range_m; },
                     "mark_range_m must be in (0, clear_range_m]");
        return t;
    }();
    return table;
}

}  // namespace makeway::costmap

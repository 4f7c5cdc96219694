#include "makeway/planning/param_tables.hpp"

namespace makeway::planning {

const ParamTable<AStarParams>& astar_table() {
    static const ParamTable<AStarParams> table = [] {
        ParamTable<AStarParams> t;
        t.add("cost_weight", &AStarParams::cost_weight, closed(0.0, 100.0),
              "a step costs its length x (1 + this x cost / 252)")
            .add("allow_unknown", &AStarParams::allow_unknown, "plans may cross cells never seen");
        return t;
    }();
    return table;
}

const ParamTable<CollisionMonitorParams>& collision_monitor_table() {
    using C = CollisionMonitorParams;
    static const ParamTable<C> table = [] {
        ParamTable<C> t;
        t.add("enabled", &C::enabled, "")
            .add("latency_s", &C::latency_s, closed(0.0, 2.0),
                 "sweep age + one control period: how long a command runs before the next check "
                 "can change it")
            .add("min_points", &C::min_points, closed(1, 100000),
                 "returns in a zone before it acts")
            .add("stop_padding_m", &C::stop_padding_m, closed(0.0, 1.0),
                 "stop zone: footprint + this along the command for latency_s, then braking (2.5 "
                 "sigma of the LiDAR's range noise)")
            .add("slowdown_padding_m", &C::slowdown_padding_m, closed(0.0, 2.0),
                 "slowdown zone: footprint + this, swept ...")
            .add("slowdown_time_s", &C::slowdown_time_s, closed(0.0, 10.0),
                 "... along the command this much longer before braking")
            .add("slowdown_ratio", &C::slowdown_ratio, above(0.0, 1.0),
                 "inside the slowdown zone: at most this share of the top speed (a cap: DWA "
                 "samples around the current speed)")
            .add("time_before_collision_s", &C::time_before_collision_s, closed(0.0, 10.0),
                 "approach: the command slowed so that contact stays at least this far ahead (0: "
                 "off)")
            .add("simulation_time_step_s", &C::simulation_time_step_s, closed(0.005, 1.0),
                 "the zones' time step along the predicted motion")
            .add("dynamic_speed_mps", &C::dynamic_speed_mps, closed(0.0, 5.0),
                 "returns new in this sweep (people) may move this fast: their stop and approach "
                 "padding grows with it")
            .add("dynamic_history", &C::dynamic_history, closed(1, 100),
                 "new: a return in the cell (or next to it) in fewer than dynamic_min_seen ...")
            .add("dynamic_min_seen", &C::dynamic_min_seen, closed(1, 100),
                 "... of the last dynamic_history sweeps (2: a walker turning back over cells it "
                 "left stays new; off: README)")
            .add("dynamic_min_seen_off_chairs", &C::dynamic_min_seen_off_chairs, closed(0, 100),
                 "... away from every known chair (personal_space_object_margin_m) this many "
                 "instead, when larger (2: a walker turning back stays new, a pulled chair does "
                 "not; a robot without an object map keeps dynamic_min_seen; 0: off)")
            .add("dynamic_cluster_m", &C::dynamic_cluster_m, closed(0.0, 2.0),
                 "> 0: a mover stays one, returns about this close to a mover (this sweep or "
                 "those) move too (off: README) ...")
            .add("dynamic_cluster_min_new", &C::dynamic_cluster_min_new, closed(1, 1000),
                 "... a mover: a cell that size with this many new returns (not a sliver out of a "
                 "shadow)")
            .add("dynamic_min_height_m", &C::dynamic_min_height_m, closed(0.0, 3.0),
                 "... and at least this high (lower: the floor's noise where the lowest rings "
                 "graze it)")
            .add("dynamic_memory_s", &C::dynamic_memory_s, closed(0.0, 10.0),
                 "a mover is remembered this long (padding growing with its age) until seen again: "
                 "a walker turning back or inside "
                 "the minimum range (0: off; README)")
            .add("dynamic_memory_range_m", &C::dynamic_memory_range_m, above(0.0, 10.0),
                 "... movers this close to the base (farther, the next sweeps see them again) ...")
            .add("dynamic_memory_min_new", &C::dynamic_memory_min_new, closed(1, 1000),
                 "... with this many new returns within 0.2 m (a body, not a sliver of wall out of "
                 "a shadow)")
            .add("dynamic_personal_space_m", &C::dynamic_personal_space_m, closed(0.0, 2.0),
                 "a new return this close to the footprint holds the robot whatever the command "
                 "(0: off; README) ...")
            .add("personal_space_object_margin_m", &C::personal_space_object_margin_m,
                 closed(0.0, 1.0),
                 "... unless it lies this close to a known chair (a pulled chair, not a walker)")
            .add("dynamic_turn_space_m", &C::dynamic_turn_space_m, closed(0.0, 2.0),
                 "a new return this close to the footprint, not beside a known chair, caps the "
                 "turn rate (a corner sweeps into a walker beside it; 0: off; README) ...")
            .add("dynamic_turn_max_radps", &C::dynamic_turn_max_radps, above(0.0, 10.0),
                 "... at this")
            .add("min_scale", &C::min_scale, below(0.0, 1.0),
                 "an approach scale below this holds the robot")
            .add(
                "lowest_beam_deg", &C::lowest_beam_deg, closed(-90.0, 90.0),
                "the LiDAR's lowest beam (VLP-32C; a VLP-16: -15); with robot.lidar_height_m: what "
                "it cannot see near it")
            .add("blind_memory_s", &C::blind_memory_s, closed(0.0, 60.0),
                 "returns the sensor can no longer see (a chair leg it closes in on) are "
                 "remembered at most this long")
            .add("low_edge_support", &C::low_edge_support, closed(0, 24),
                 "a low return seen in one sweep only (a table foot 3 cm high) is remembered with "
                 "this many returns around it "
                 "(5 x 5 cells; 0: never)")
            .add("object_footprints", &C::object_footprints,
                 "inside that blind ring the object map's chairs count as returns (a pulled "
                 "chair's base is not seen) ...")
            .add("object_moving_mps", &C::object_moving_mps, closed(0.0, 10.0),
                 "... those that moved faster than this in the last blind_memory_s (a box also "
                 "covers the backrest above the body)")
            .add("object_lead_s", &C::object_lead_s, closed(0.0, 5.0),
                 "... each swept along its velocity this far ahead (the object map lags a "
                 "keyframe; 0: where it is)")
            .add("object_parts", &C::object_parts,
                 "inside that blind ring the body-height parts of every object placed by its CAD "
                 "model count as returns (a round table's foot, an office chair's star base), "
                 "for blind_memory_s after the object map drops one")
            .add("bridge_gap_m", &C::bridge_gap_m, closed(0.0, 0.4),
                 "a gap this narrow between two still returns counts as solid (a chair's seat "
                 "between its back's posts; never wider than the footprint's width - 3 cm); 0: off")
            .add("max_range_m", &C::max_range_m, above(0.0, 50.0),
                 "returns farther than this from the base are not looked at")
            .add("recovery_after_s", &C::recovery_after_s, above(0.0, 3600.0),
                 "held this long: back up into space the sweep shows free, else turn on the spot")
            .add("backup_speed_mps", &C::backup_speed_mps, above(0.0, 5.0), "")
            .add("backup_distance_m", &C::backup_distance_m, closed(0.0, 10.0), "")
            .add("rotate_speed_radps", &C::rotate_speed_radps, above(0.0, 10.0), "")
            .add("rotate_angle_rad", &C::rotate_angle_rad, closed(0.0, 10.0), "")
            .add("give_way_horizon_s", &C::give_way_horizon_s, closed(0.0, 5.0),
                 "give way: a moving object the object map knows of (a chair being pulled out) "
                 "that would come within give_way_margin_m of the robot standing this soon ...; "
                 "0: off")
            .add("give_way_margin_m", &C::give_way_margin_m, closed(0.0, 1.0),
                 "... within this of the footprint ...")
            .add("give_way_speed_mps", &C::give_way_speed_mps, above(0.0, 5.0),
                 "... moves the robot off, straight back or on at this speed or half of it "
                 "(whichever keeps more clearance and passes the stop check), or holds it")
            .add("give_way_min_speed_mps", &C::give_way_min_speed_mps, closed(0.0, 5.0),
                 "chairs moving at least this fast are given way to (the object map's velocity, "
                 "else ...")
            .add("give_way_window_s", &C::give_way_window_s, above(0.0, 10.0),
                 "... its box's displacement over this long: the map holds a chair at rest until "
                 "it moved 0.3 m)")
            .add("give_way_lag_s", &C::give_way_lag_s, closed(0.0, 5.0),
                 "a moving chair's box was measured this long before the cycle it changed in "
                 "(the keyframe's sweeps, the filter): carried along its velocity to now")
            .require([](const C& c) { return c.slowdown_padding_m >= c.stop_padding_m; },
                     "slowdown_padding_m must be in [stop_padding_m, 2]")
            .require([](const C& c) { return c.dynamic_min_seen <= c.dynamic_history; },
                     "dynamic_min_seen must be in [1, dynamic_history]")
            .require([](const C& c) { return c.dynamic_min_seen_off_chairs <= c.dynamic_history; },
                     "dynamic_min_seen_off_chairs must be in [0, dynamic_history]");
        return t;
    }();
    return table;
}

const ParamTable<DwaParams>& dwa_table() {
    using D = DwaParams;
    static const ParamTable<D> table = [] {
        ParamTable<D> t;
        t.add("horizon_s", &D::horizon_s, above(0.0, 10.0), "rollouts this long")
            .add("lookahead_m", &D::lookahead_m, above(0.0, 20.0),
                 "carrot distance along the global path")
            .add("plan_envelope", &D::plan_envelope,
                 "DWA keeps to the costs the global plan accepts (no cutting through zones the "
                 "plan went around)")
            .add("envelope_margin", &D::envelope_margin, closed(0.0, 252.0),
                 "cost units above the plan's highest cost still inside the envelope")
            .require([](const D& d) { return d.horizon_s >= d.rollout_dt_s; },
                     "need 0 < rollout_dt_s <= horizon_s");
        return t;
    }();
    return table;
}

}  // namespace makeway::planning

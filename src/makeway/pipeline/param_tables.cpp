#include "makeway/pipeline/param_tables.hpp"

#include "makeway/perception/param_tables.hpp"

namespace makeway::pipeline {

const ParamTable<KeyframeParams>& keyframe_table() {
    using K = KeyframeParams;
    static const ParamTable<K> table = [] {
        ParamTable<K> t;
        t.add("keyframe_window", &K::window, closed(1, 100),
              "sweeps accumulated into a keyframe (de-skewed, newest sweep's frame)")
            .add("keyframe_every", &K::every, closed(1, 1000),
                 "sweeps between keyframes (10 Hz sweeps: 2 Hz keyframes)")
            .add("deskew", &K::deskew, "move each point with the sensor pose at its own time")
            .include(
                "ground_", [](K& k) -> perception::GroundPlaneParams& { return k.ground; },
                perception::ground_plane_table())
            .include(
                "", [](K& k) -> perception::GroundFilterParams& { return k.ground_filter; },
                perception::ground_filter_table());
        return t;
    }();
    return table;
}

const ParamTable<NavigatorParams>& navigator_policy_table() {
    using N = NavigatorParams;
    static const ParamTable<N> table = [] {
        ParamTable<N> t;
        t.add("replan_period_s", &N::replan_period_s, above(0.0, 600.0),
              "the global plan is renewed at least this often")
            .add("plan_switch_margin", &N::plan_switch_margin, closed(0.0, 10.0),
                 "a renewed plan replaces the one being followed (still free) only when that one's "
                 "rest costs more than (1 + this) times the new one (0: always the newest)")
            .add("blocked_lookahead_m", &N::blocked_lookahead_m, above(0.0, 100.0),
                 "a lethal cell on the plan this far ahead forces a replan ...")
            .add("blocked_ignore_m", &N::blocked_ignore_m, closed(0.0, 100.0),
                 "... unless it is this close to the robot")
            .add("turn_target_index", &N::turn_target_index, closed(1, 1000),
                 "no safe velocity: turn on the spot toward this plan point")
            .add("turn_rate_radps", &N::turn_rate_radps, above(0.0, 10.0), "")
            .add("turn_clear_rad", &N::turn_clear_rad, closed(0.0, 3.2),
                 "... only where the bare footprint turned this far stays off lethal cells (0: "
                 "unchecked)")
            .add("stuck_progress_m", &N::stuck_progress_m, above(0.0, 10.0),
                 "the way left along the plan shrinking by less than this ...")
            .add("stuck_timeout_s", &N::stuck_timeout_s, above(0.0, 600.0),
                 "... for this long: back up, then replan")
            .add("backup_speed_mps", &N::backup_speed_mps, above(0.0, 5.0), "")
            .add("backup_duration_s", &N::backup_duration_s, above(0.0, 60.0), "")
            .add("standstill_timeout_s", &N::standstill_timeout_s, above(0.0, 600.0),
                 "DWA's best velocity a standstill this long: stuck now (back up, replan around)")
            .add("standstill_v_mps", &N::standstill_v_mps, above(0.0, 1.0),
                 "standstill: slower than this ...")
            .add("standstill_w_radps", &N::standstill_w_radps, above(0.0, 1.0),
                 "... turning slower than this")
            .add("waypoint_tolerance_m", &N::waypoint_tolerance_m, above(0.0, 10.0),
                 "a waypoint counts as reached this close")
            .add("goal_tolerance_m", &N::goal_tolerance_m, above(0.0, 10.0),
                 "the goal counts as reached this close (own pose estimate)")
            .add(
                "give_up_s", &N::give_up_s, above(0.0, 3600.0),
                "no plan, or no progress along it despite recoveries, this long: the mission fails")
            .add("detour_ahead_m", &N::detour_ahead_m, closed(0.0, 10.0),
                 "stuck: A* avoids the plan's point this far ahead ...")
            .add("detour_radius_m", &N::detour_radius_m, closed(0.0, 5.0),
                 "... this wide (0: never) ...")
            .add("detour_memory_s", &N::detour_memory_s, closed(0.0, 3600.0), "... this long ...")
            .add("max_detours", &N::max_detours, closed(0, 100),
                 "... this often per leg (no other way: through it again)")
            .add("clocked_detours", &N::clocked_detours, closed(0, 100),
                 "the leg's first this many detours get give_up_s of their own (progress along "
                 "the longer way around)")
            .add("plan_to_tolerance", &N::plan_to_tolerance, below(0.0, 1.0),
                 "A* ends anywhere within this share of the tolerance (a goal inside a zone is "
                 "approached from its cheap side)")
            .require([](const N& n) { return n.blocked_ignore_m < n.blocked_lookahead_m; },
                     "blocked_ignore_m must be in [0, blocked_lookahead_m)");
        return t;
    }();
    return table;
}

const ParamTable<TrackedShapeParams>& tracked_shape_table() {
    using T = TrackedShapeParams;
    static const ParamTable<T> table = [] {
        ParamTable<T> t;
        t.add("match_distance_m", &T::match_distance_m, above(0.0, 10.0),
              "a segment this close to a tracked object's learned shape is verified against it")
            .add("max_views", &T::max_views, closed(1, 1000),
                 "the latest views of a tracked object fused into its learned shape")
            .add("view_margin_m", &T::view_margin_m, closed(0.0, 2.0),
                 "a view: the keyframe's returns in the fitted box grown by this");
        return t;
    }();
    return table;
}

}  // namespace makeway::pipeline

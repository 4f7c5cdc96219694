#include "makeway/pipeline/online_system.hpp"

#include <cmath>
#include <iterator>

#include "makeway/common/stopwatch.hpp"

namespace makeway::pipeline {
namespace {

// The sweep without its points: what control() reads (stamps, wheel odometry) once the points
// have moved into the pipeline.
Sweep stamps_of(const Sweep& s) {
    return {{}, s.stamp_s, s.duration_s, s.odometry_start, s.odometry_end};
}

Costmap map_of(const OnlineSystemSetup& s) {
    return s.map ? *s.map : free_area(s.start, s.free_area_m, s.free_area_resolution_m);
}

// Velocity over `dt` from two poses of the base (an increment in the first pose's frame).
std::pair<double, double> velocity_between(const Pose2& a, const Pose2& b, double dt) {
    if (!(dt > 1e-6)) return {0.0, 0.0};
    const Isometry2 delta = to_isometry(a).inverse() * to_isometry(b);
    return {delta.translation().x() / dt,
            std::atan2(delta.linear()(1, 0), delta.linear()(0, 0)) / dt};
}

}  // namespace

Costmap free_area(const Pose2& centre, double side_m, double resolution_m) {
    const int cells = static_cast<int>(side_m / resolution_m);
    return Costmap(
        Eigen::Vector2d(centre.x_m, centre.y_m) - Eigen::Vector2d::Constant(0.5 * side_m),
        resolution_m, cells, cells);
}

Controller::Controller(const Costmap& static_map, const NavigatorParams& params)
    : navigator_(static_map, params),
      monitor_(params.monitor),
      min_existence_(params.affordance.min_existence),
      object_map_(params.affordance_layer),
      moving_chairs_(params.monitor.give_way_min_speed_mps, params.monitor.give_way_window_s,
                     params.monitor.give_way_lag_s) {}

void Controller::set_route(std::vector<Eigen::Vector2d> legs_m) {
    navigating_ = !legs_m.empty();
    navigator_.set_route(std::move(legs_m));
}

Polygon2 chair_footprint(const ObjectEstimate& o, double lead_s) {
    const auto c = o.box_world.bev_corners();
    Polygon2 out(c.begin(), c.end());
    if (lead_s <= 0.0 || o.velocity_mps.squaredNorm() == 0.0) return out;
    for (const auto& q : c) out.push_back(q + lead_s * o.velocity_mps);
    return convex_hull(std::move(out));
}

MovingChairs::MovingChairs(double min_speed_mps, double window_s, double lag_s)
    : min_speed_mps_(min_speed_mps), window_s_(window_s), lag_s_(lag_s) {}

std::vector<planning::MovingOutline> MovingChairs::update(
    double t_s, const std::vector<ObjectEstimate>& objects, double min_existence) {
    std::erase_if(centres_,
                  [&](const auto& kv) { return t_s - kv.second.back().first > window_s_; });
    std::vector<planning::MovingOutline> out;
    for (const ObjectEstimate& o : objects) {
        if (o.cls != ObjectClass::kChair || o.existence < min_existence) continue;
        auto& seen = centres_[o.id];
        seen.emplace_back(t_s, o.box_world.centre_m.head<2>());
        while (seen.size() > 1 && t_s - seen[1].first >= window_s_) seen.pop_front();
        Eigen::Vector2d v = o.velocity_mps;
        const double span = t_s - seen.front().first;
        if (v.norm() < min_speed_mps_ && span >= window_s_ - 1e-9)  // a whole window: no noise
            v = (seen.back().second - seen.front().second) / span;
        if (v.norm() < min_speed_mps_) continue;
        // A moving chair's box changes with every keyframe that measures it: it was measured
        // when it last changed, lag_s before that (the keyframe's sweeps, the filter), and the
        // chair moved on since. Carried along its velocity to now, not where it was.
        auto since = seen.rbegin();
        while (std::next(since) != seen.rend() && std::next(since)->second == seen.back().second)
            ++since;
        const double age_s = t_s - since->first + lag_s_;
        Polygon2 outline = chair_footprint(o, 0.0);
        for (Eigen::Vector2d& q : outline) q += age_s * v;
        out.push_back({std::move(outline), v});
    }
    return out;
}

Controller::Step Controller::step(const NavigatorInput& in) {
    Step out;
    out.navigating = navigating_;
    out.nav = navigator_.step(in);
    const VelocityCommand wanted =
        navigating_ && !out.nav.arrived && !out.nav.gave_up ? out.nav.command : VelocityCommand{};
    if (out.nav.arrived || out.nav.gave_up) navigating_ = false;
    const SteadyClock::time_point t0 = SteadyClock::now();
    // A chair someone moves can come up beside the robot where the sensor sees its seat but not
    // its base, and the monitor's memory has it where it was: while a chair has moved in the last
    // blind_memory_s its footprint stands in for the base (a box also covers the backrest above
    // the body, so a still chair is left to the sweep and the memory). Chairs only: tables are
    // open below their top. Every chair goes to the monitor's test of what is a walker (new returns
    // beside one are that chair being pulled, not a walker).
    const planning::CollisionMonitorParams& mp = monitor_.params();
    std::erase_if(moved_at_, [&](const auto& kv) {
        return in.t_s - kv.second > mp.blind_memory_s;
    });  // a long run's ids do not pile up
    std::erase_if(parts_,
                  [&](const auto& kv) { return in.t_s - kv.second.t_s > mp.blind_memory_s; });
    std::vector<Polygon2> chairs, solid;
    const std::vector<planning::MovingOutline> movers =
        mp.give_way_horizon_s > 0.0 ? moving_chairs_.update(in.t_s, in.objects, min_existence_)
                                    : std::vector<planning::MovingOutline>{};
    for (const ObjectEstimate& o : in.objects) {
        if (o.existence < min_existence_) continue;
        bool moving = false;
        if (o.cls == ObjectClass::kChair) {
            if (o.velocity_mps.norm() > mp.object_moving_mps) moved_at_[o.id] = in.t_s;
            const auto moved = moved_at_.find(o.id);
            moving = moved != moved_at_.end() && in.t_s - moved->second <= mp.blind_memory_s;
            chairs.push_back(chair_footprint(o, moving ? mp.object_lead_s : 0.0));
            if (moving && mp.object_footprints) solid.push_back(chairs.back());
        }
        // What a CAD model placed: the parts the body can hit, whatever the class (a table's foot
        // is as low as a chair's base), a moving chair's where they are now (its box above). Kept
        // for blind_memory_s after the map drops the object: too close to the robot to be
        // detected, it is still there.
        if (mp.object_parts && !o.parts_world.empty()) parts_[o.id] = {o.parts_world, in.t_s};
    }
    for (const auto& [id, kept] : parts_)
        solid.insert(solid.end(), kept.parts.begin(), kept.parts.end());
    // Without the object-aware layer (the con and oppo baselines) the robot has no object map:
    // the monitor is told so, not that the room holds no chair.
    out.guard = monitor_.filter({in.t_s, in.pose, in.points_world, wanted, in.v_mps, in.w_radps,
                                 &solid, object_map_ ? &chairs : nullptr, &movers});
    out.monitor_ms = ms_since(t0);
    // Idle (never driven, arrived, gave up, cancelled): zero, whatever the monitor was doing (a
    // recovery it had started is not a goal's to finish).
    out.command = out.navigating && navigating_ ? out.guard.command : VelocityCommand{};
    return out;
}

OnlineSystem::OnlineSystem(const OnlineSystemSetup& setup)
    : static_map_(map_of(setup)),
      pipeline_(setup.params, setup.start, setup.detector, setup.library),
      controller_(static_map_, setup.params.navigator) {
    pipeline_.set_shape_prior(setup.prior);
    if (setup.map && setup.map_kind == MapKind::kWalls) {
        // A map of walls: objects stand in its free space.
        pipeline_.set_object_region([this](const Eigen::Vector2d& p) {
            const auto c = static_map_.cost_at(p);
            return c.has_value() && *c < cost::kLethal;
        });
    } else if (setup.map && setup.map_kind == MapKind::kFurnished) {
        // Within the map's known area. Not "in its free space" as with a map of walls alone: a
        // SLAM map of a furnished room holds the furniture as occupied cells.
        pipeline_.set_object_region([this](const Eigen::Vector2d& p) {
            const auto c = static_map_.cost_at(p);
            return c.has_value() && *c != cost::kUnknown;
        });
    }
}

OnlineStep OnlineSystem::process(Sweep sweep) {
    OnlineStep out;
    const Sweep stamps = stamps_of(sweep);
    out.sweep = pipeline_.process_sweep(std::move(sweep));
    control(stamps, out);
    return out;
}

OnlineStep OnlineSystem::drive(Sweep sweep, std::optional<PendingKeyframe>* pending) {
    OnlineStep out;
    const Sweep stamps = stamps_of(sweep);
    out.sweep = pipeline_.track(std::move(sweep), pending);
    control(stamps, out);
    return out;
}

void OnlineSystem::control(const Sweep& sweep, OnlineStep& out) {
    // The velocity as the robot measures it: the wheel odometry's increment over the sweep (else
    // the pose estimate's since the last sweep).
    if (sweep.odometry_start && sweep.odometry_end) {
        std::tie(out.v_mps, out.w_radps) =
            velocity_between(*sweep.odometry_start, *sweep.odometry_end, sweep.duration_s);
    } else if (last_pose_) {
        std::tie(out.v_mps, out.w_radps) =
            velocity_between(*last_pose_, out.sweep.pose, sweep.duration_s);
    }
    last_pose_ = out.sweep.pose;
    out.control = controller_.step({sweep.stamp_s + sweep.duration_s, out.sweep.pose, out.v_mps,
                                    out.w_radps, &out.sweep.points_world,
                                    out.sweep.T_world_sensor_end.translation(), out.sweep.objects});
}

}  // namespace makeway::pipeline

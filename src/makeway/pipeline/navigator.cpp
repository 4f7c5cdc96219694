#include "makeway/pipeline/navigator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "makeway/common/angles.hpp"
#include "makeway/common/stopwatch.hpp"
#include "makeway/planning/dwa.hpp"

namespace makeway::pipeline {

namespace {

// DWA never picks a velocity the collision monitor would stop: its rollouts keep the monitor's
// stop padding clear of lethal cells (else the robot creeps at a gap the monitor will not let it
// through, until it gives up). A* agrees with them: a cell is inscribed (never planned through)
// when the padded footprint cannot stand there at any heading, so it never plans through a gap
// 0.43-0.51 m wide that DWA then refuses (measured: 4 of gt-perc's 6 failures on 100 scenes).
NavigatorParams with_monitor_padding(NavigatorParams p) {
    const double padding = p.monitor.enabled
                               ? std::max(p.dwa.footprint_padding_m, p.monitor.stop_padding_m)
                               : p.dwa.footprint_padding_m;
    p.dwa.footprint_padding_m = padding;
    p.inflation.inscribed_radius_m += padding;
    p.inflation.inflation_radius_m =
        std::max(p.inflation.inflation_radius_m, p.inflation.inscribed_radius_m);
    return p;
}

}  // namespace

const char* to_string_state(const NavigatorStep& s) {
    if (s.arrived) return "arrived";
    if (s.gave_up) return "gave_up";
    if (s.recovering) return "backing_up";
    if (!s.dwa_found) return "turning";
    if (!s.has_plan) return "no_plan";
    return "following";
}

Navigator::Navigator(const Costmap& static_map, const NavigatorParams& params)
    : params_(with_monitor_padding(params)), costmap_(static_map, params_) {}

void Navigator::set_route(std::vector<Eigen::Vector2d> legs_m) {
    legs_ = std::move(legs_m);
    leg_ = 0;
    plan_.clear();
    started_ = false;  // a new route: its own progress and give-up clocks
    recovery_until_ = -1.0;
    avoided_.clear();
    detours_ = 0;
    detour_pending_ = false;
    standstill_since_ = -1.0;
}

NavigatorStep Navigator::step(const NavigatorInput& in) {
    const auto t0 = SteadyClock::now();
    NavigatorStep out;
    const Eigen::Vector2d here(in.pose.x_m, in.pose.y_m);
    // Costmap: every layer grows the update window, then writes inside it (also without a route:
    // the map is kept while the robot waits for a goal).
    costmap_.update(in.points_world, in.sensor_world_m, in.objects);
    // Legs: waypoints, then the goal, judged on the pose estimate.
    if (leg_ < legs_.size() &&
        (here - legs_[leg_]).norm() <
            (leg_ + 1 == legs_.size() ? params_.goal_tolerance_m : params_.waypoint_tolerance_m)) {
        ++leg_;
        plan_.clear();
        out.reached_waypoint = true;
    }
    if (arrived()) {
        out.arrived = true;
        out.update_ms = ms_since(t0);
        return out;
    }
    check_progress(in, out);
    // Global plan when there is none, when it is due, or when something now blocks it. A due
    // plan replaces the one being followed only when clearly cheaper (plan_switch_margin).
    const bool blocked = !plan_.empty() && plan_blocked(here);
    if (plan_.empty() || in.t_s - last_plan_t_ >= params_.replan_period_s || blocked) {
        bool around = false;
        double kept_cost = std::numeric_limits<double>::infinity(), new_cost = 0.0;
        const bool may_keep = params_.plan_switch_margin > 0.0 && !plan_.empty() && !blocked;
        const planning::PlanResult p =
            plan(here, in.t_s, around, may_keep ? &kept_cost : nullptr, &new_cost);
        if (p.status == planning::PlanStatus::kOk) {
            const bool keep = may_keep && std::isfinite(kept_cost) &&
                              kept_cost <= new_cost * (1.0 + params_.plan_switch_margin);
            if (!keep) plan_ = p.path_m;
            out.kept_plan = keep;
            planned_t_ = in.t_s;
            if (detour_pending_ && around) {
                // The first plan around each of the leg's first clocked_detours stuck spots is
                // longer than the way that failed: it gets give_up_s of its own, progress measured
                // along it. Not every detour: a robot circling from detour to detour (con in the
                // demo's study space: 121.7 s with 3, 51.4 s with 2) still gives up, at most
                // about (clocked_detours + 1) x give_up_s after it last came closer.
                best_remaining_m_ = remaining_m(here);
                moved_t_ = in.t_s;
            }
            detour_pending_ = false;
        }
        out.plan_status = p.status;
        last_plan_t_ = in.t_s;
        out.replanned = true;
    }
    // A robot that cannot plan, or cannot make progress, gives up instead of waiting forever.
    if (in.t_s - planned_t_ > params_.give_up_s || in.t_s - moved_t_ > params_.give_up_s) {
        out.gave_up = true;
        out.update_ms = ms_since(t0);
        return out;
    }
    // Local control: back up while recovering, else DWA along the plan.
    out.recovering = in.t_s < recovery_until_;
    out.has_plan = !plan_.empty();
    if (out.recovering) {
        out.command = {-params_.backup_speed_mps, 0.0};
    } else if (!plan_.empty()) {
        out.command = follow_plan(in, out);
        // DWA's best velocity a standstill: every way forward along the plan collides within the
        // horizon (a gap entered at an angle its footprint does not turn in). Waiting for
        // stuck_timeout_s would only wait; after standstill_timeout_s it is stuck now.
        const bool still = out.dwa_found &&
                           std::abs(out.command.v_mps) < params_.standstill_v_mps &&
                           std::abs(out.command.w_radps) < params_.standstill_w_radps;
        if (!still) {
            standstill_since_ = -1.0;
        } else if (standstill_since_ < 0.0) {
            standstill_since_ = in.t_s;
        } else if (in.t_s - standstill_since_ >= params_.standstill_timeout_s) {
            standstill_since_ = -1.0;
            start_recovery(in, out);
            out.recovering = true;
            out.command = {-params_.backup_speed_mps, 0.0};
        }
    }
    out.update_ms = ms_since(t0);
    return out;
}

planning::PlanResult Navigator::plan(const Eigen::Vector2d& here, double t_s, bool& around,
                                     double* kept_cost, double* new_cost) {
    // The plan ends inside the leg's tolerance (a goal in a zone is reached from its cheap side),
    // short enough of the tolerance that the robot still crosses it on its pose estimate.
    const double tolerance =
        leg_ + 1 == legs_.size() ? params_.goal_tolerance_m : params_.waypoint_tolerance_m;
    const double radius = params_.plan_to_tolerance * tolerance;
    std::erase_if(avoided_, [&](const Avoided& a) { return a.until_s <= t_s; });
    // The new plan and the rest of the one being followed (from the robot straight to its
    // nearest point, then along it), costed alike on the map A* searched.
    auto costs = [&](const Costmap& map, const planning::PlanResult& p) {
        if (p.status != planning::PlanStatus::kOk || !kept_cost || plan_.empty()) return;
        *new_cost = planning::path_cost(map, p.path_m, params_.astar);
        std::vector<Eigen::Vector2d> rest{here};
        rest.insert(rest.end(),
                    plan_.begin() + static_cast<std::ptrdiff_t>(nearest_plan_index(here)),
                    plan_.end());
        *kept_cost = planning::path_cost(map, rest, params_.astar);
    };
    if (!avoided_.empty()) {
        // Around the spots the robot got stuck at: their discs lethal on a copy of the costmap
        // (never under the robot itself, which must stay a valid start).
        Costmap map = costmap_.master();
        const double r = params_.detour_radius_m;
        for (const Avoided& a : avoided_) {
            const GridWindow win =
                map.window_of(a.at_m - Eigen::Vector2d(r, r), a.at_m + Eigen::Vector2d(r, r));
            for (int y = win.y0; y < win.y1; ++y) {
                for (int x = win.x0; x < win.x1; ++x) {
                    const Eigen::Vector2d w = map.centre_of(x, y);
                    if ((w - a.at_m).norm() > r ||
                        (w - here).norm() < params_.inflation.inscribed_radius_m)
                        continue;
                    map.at(x, y) = cost::kLethal;
                }
            }
        }
        planning::PlanResult p =
            planning::plan_astar(map, here, legs_[leg_], params_.astar, radius);
        if (p.status == planning::PlanStatus::kOk) {
            around = true;
            costs(map, p);
            return p;
        }
        // No other way: through the stuck spot again.
    }
    planning::PlanResult p =
        planning::plan_astar(costmap_.master(), here, legs_[leg_], params_.astar, radius);
    costs(costmap_.master(), p);
    return p;
}

std::size_t Navigator::nearest_plan_index(const Eigen::Vector2d& robot) const {
    std::size_t nearest = 0;
    for (std::size_t i = 1; i < plan_.size(); ++i) {
        if ((plan_[i] - robot).squaredNorm() < (plan_[nearest] - robot).squaredNorm()) nearest = i;
    }
    return nearest;
}

Eigen::Vector2d Navigator::along_plan(const Eigen::Vector2d& robot, double ahead_m) const {
    std::size_t i = nearest_plan_index(robot);
    for (double travelled = 0.0; i + 1 < plan_.size() && travelled < ahead_m; ++i)
        travelled += (plan_[i + 1] - plan_[i]).norm();
    return plan_[i];
}

bool Navigator::plan_blocked(const Eigen::Vector2d& robot) const {
    const Costmap& m = costmap_.master();
    const std::size_t nearest = nearest_plan_index(robot);
    double travelled = 0.0;
    for (std::size_t i = nearest; i < plan_.size() && travelled < params_.blocked_lookahead_m;
         ++i) {
        if (i > nearest) travelled += (plan_[i] - plan_[i - 1]).norm();
        const auto c = m.cost_at(plan_[i]);
        if (c && *c >= cost::kInscribed && *c != cost::kUnknown &&
            (plan_[i] - robot).norm() > params_.blocked_ignore_m)
            return true;
    }
    return false;
}

VelocityCommand Navigator::follow_plan(const NavigatorInput& in, NavigatorStep& out) const {
    const planning::DwaResult r =
        planning::dwa_step(costmap_.master(), {in.pose, in.v_mps, in.w_radps}, plan_, params_.dwa);
    out.dwa_found = r.found;
    if (r.found) return r.command;
    // Every velocity collides: turn toward the path on the spot where the turn is clear, else
    // stand (without progress for stuck_timeout_s, the stuck recovery backs the robot up).
    const auto k = static_cast<std::size_t>(params_.turn_target_index);
    const Eigen::Vector2d target = plan_.size() > k ? plan_[k] : plan_.back();
    const double heading = std::atan2(target.y() - in.pose.y_m, target.x() - in.pose.x_m);
    const double toward = std::copysign(1.0, angle_diff(heading, in.pose.yaw_rad));
    if (!turn_clear(in.pose, toward)) return {};
    return {0.0, toward * params_.turn_rate_radps};
}

bool Navigator::turn_clear(const Pose2& pose, double sign) const {
    // The turn is checked against the costmap's lethal cells, which keep what the obstacle layer
    // marked from farther away (a chair's leg) where the monitor's latest sweep, inside the
    // sensor's blind ring, no longer shows it; a turning corner sweeps at the turn rate times its
    // reach (0.33 m/s at 1 rad/s). The bare footprint (no padding: DWA, with it, found every
    // velocity colliding), and only cells the turn would bring it onto: one it already stands on
    // does not hold it.
    if (params_.turn_clear_rad <= 0.0) return true;
    planning::DwaParams bare = params_.dwa;
    bare.footprint_padding_m = 0.0;
    if (planning::footprint_collides(costmap_.master(), pose, bare)) return true;
    constexpr double kStep_rad = 0.05;
    for (double a = kStep_rad; a < params_.turn_clear_rad + kStep_rad; a += kStep_rad) {
        Pose2 q = pose;
        q.yaw_rad = wrap_angle(pose.yaw_rad + sign * std::min(a, params_.turn_clear_rad));
        if (planning::footprint_collides(costmap_.master(), q, bare)) return false;
    }
    return true;
}

double Navigator::remaining_m(const Eigen::Vector2d& robot) const {
    // Along the plan from its point nearest the robot; straight to the target without a plan.
    if (plan_.empty()) return leg_ < legs_.size() ? (legs_[leg_] - robot).norm() : 0.0;
    const std::size_t nearest = nearest_plan_index(robot);
    double left = (plan_[nearest] - robot).norm();
    for (std::size_t i = nearest + 1; i < plan_.size(); ++i)
        left += (plan_[i] - plan_[i - 1]).norm();
    return left;
}

void Navigator::check_progress(const NavigatorInput& in, NavigatorStep& out) {
    // Progress is the way left to the leg's target getting shorter than it has ever been on this
    // leg by stuck_progress_m; motion alone is not progress (a robot circling in front of a gap it
    // cannot pass moves all the time). None for stuck_timeout_s: back up for backup_duration_s,
    // then replan; none for give_up_s (step()): the mission fails.
    const Eigen::Vector2d here(in.pose.x_m, in.pose.y_m);
    const double left = remaining_m(here);
    if (!started_ || progress_leg_ != leg_ || left < best_remaining_m_ - params_.stuck_progress_m) {
        if (!started_) planned_t_ = in.t_s;
        if (!started_ || progress_leg_ != leg_) detours_ = 0;
        started_ = true;
        progress_leg_ = leg_;
        moved_t_ = in.t_s;
        best_remaining_m_ = left;
        progress_t_ = in.t_s;
    } else if (in.t_s - progress_t_ > params_.stuck_timeout_s && in.t_s >= recovery_until_) {
        start_recovery(in, out);
    }
}

void Navigator::start_recovery(const NavigatorInput& in, NavigatorStep& out) {
    const Eigen::Vector2d here(in.pose.x_m, in.pose.y_m);
    recovery_until_ = in.t_s + params_.backup_duration_s;
    progress_t_ = in.t_s + params_.backup_duration_s;
    if (!plan_.empty() && detours_ < params_.max_detours && params_.detour_radius_m > 0.0) {
        // The plan leads where the robot cannot go: the next plan goes around that spot.
        avoided_.push_back(
            {along_plan(here, params_.detour_ahead_m), in.t_s + params_.detour_memory_s});
        ++detours_;
        out.detour = true;
        detour_pending_ = detours_ <= params_.clocked_detours;  // the leg's first ones (step())
    }
    plan_.clear();
    out.started_recovery = true;
}

}  // namespace makeway::pipeline

// What the collision monitor does about what its zones find (collision_monitor.hpp): pass or
// scale the command, hold the robot and, held for a while, recover; give way to what moves.
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "makeway/planning/collision_monitor.hpp"

namespace makeway::planning {

MonitorResult CollisionMonitor::decide(const MonitorInput& in, const VelocityCommand& current,
                                       const std::vector<Eigen::Vector2d>& pts,
                                       const std::vector<char>& dynamic,
                                       const std::vector<double>& age) {
    if (in.t_s < recovery_until_) {  // recovering: the recovery's own command, stop-checked
        MonitorResult r = check(recovery_command_, current, pts, dynamic, age);
        r.recovering = true;
        if (r.scale < params_.min_scale) {  // something came into the way: end the recovery, held
            recovery_until_ = -1.0;
            held_since_ = in.t_s;
            r.recovering = false;
            r.action = MonitorAction::kBlocked;
            return r;
        }
        r.action = recovery_command_.v_mps != 0.0 ? MonitorAction::kBackup : MonitorAction::kRotate;
        return r;
    }
    MonitorResult r = check(in.command, current, pts, dynamic, age);
    if (r.scale >= params_.min_scale) {
        held_since_ = -1.0;
        return r;
    }
    if (held_since_ < 0.0) held_since_ = in.t_s;
    if (in.t_s - held_since_ + 1e-9 < params_.recovery_after_s) return r;
    // Held for a while: back up into free space, else turn on the spot toward free space.
    const VelocityCommand backup{-params_.backup_speed_mps, 0.0};
    const double turn_sign = in.command.w_radps < 0.0 ? -1.0 : 1.0;
    const VelocityCommand turns[2] = {{0.0, turn_sign * params_.rotate_speed_radps},
                                      {0.0, -turn_sign * params_.rotate_speed_radps}};
    std::optional<std::pair<VelocityCommand, double>> chosen;
    if (params_.backup_distance_m > 0.0 &&
        recovery_free(backup, current, params_.backup_distance_m / params_.backup_speed_mps, pts,
                      dynamic, age)) {
        chosen = {backup, params_.backup_distance_m / params_.backup_speed_mps};
    } else {
        for (const VelocityCommand& t : turns) {
            const double d = params_.rotate_angle_rad / params_.rotate_speed_radps;
            if (params_.rotate_angle_rad > 0.0 && recovery_free(t, current, d, pts, dynamic, age)) {
                chosen = {t, d};
                break;
            }
        }
    }
    held_since_ = in.t_s;  // the next recovery (or retry) after another recovery_after_s
    if (!chosen) {
        r.action = MonitorAction::kBlocked;
        return r;
    }
    recovery_command_ = chosen->first;
    recovery_until_ = in.t_s + chosen->second;
    r.command = recovery_command_;
    r.scale = 1.0;
    r.recovering = true;
    r.started_recovery = true;
    r.action = recovery_command_.v_mps != 0.0 ? MonitorAction::kBackup : MonitorAction::kRotate;
    return r;
}

void CollisionMonitor::give_way(const MonitorInput& in, const VelocityCommand& current,
                                const std::vector<Eigen::Vector2d>& pts,
                                const std::vector<char>& dynamic, const std::vector<double>& age,
                                MonitorResult& r) {
    const Isometry2 T_base_world = to_isometry(in.pose).inverse();
    std::vector<MovingOutline> movers;
    for (const MovingOutline& m : *in.movers_world) {
        MovingOutline& b = movers.emplace_back();
        for (const Eigen::Vector2d& q : m.outline) b.outline.push_back(T_base_world * q);
        b.velocity_mps = T_base_world.linear() * m.velocity_mps;
    }
    const Eigen::Vector2d half = footprint_half();
    // Each command held for the horizon (no braking: the next cycle decides again).
    auto clearance = [&](const VelocityCommand& c) {
        return clearance_over(trajectory({current, c, params_.give_way_horizon_s, false}), half,
                              movers, params_.give_way_margin_m);
    };
    // Only what comes at the robot even if it stands: a command that drives at a mover is the
    // zones' business (a robot that waited for every chair moving ahead of it would not arrive).
    const Clearance standing = clearance({});
    if (!std::isfinite(standing.within_s)) {
        giving_way_.reset();
        return;
    }
    // Giving way already: the way off holds until the robot could stand clear, unless the
    // navigator's command (or another way off) keeps more. DWA's next command turns back into
    // the chair's way as soon as this one looks clear for the horizon.
    MonitorResult best = r;
    bool from_navigator = true;
    VelocityCommand chosen;  // as asked for, before the zones scaled it
    if (giving_way_) {
        MonitorResult m = check(*giving_way_, current, pts, dynamic, age);
        if (m.scale >= params_.min_scale) best = m, from_navigator = false, chosen = *giving_way_;
    }
    Clearance best_clearance = clearance(best.command);
    if (from_navigator && !std::isfinite(best_clearance.within_s)) return;  // it keeps clear
    const double s = params_.give_way_speed_mps;
    // Slower first: of two that keep as clear, the gentler.
    for (const VelocityCommand& c :
         {r.command, VelocityCommand{-0.5 * s, 0.0}, VelocityCommand{0.5 * s, 0.0},
          VelocityCommand{-s, 0.0}, VelocityCommand{s, 0.0}}) {
        MonitorResult m = check(c, current, pts, dynamic, age);
        if (m.scale < params_.min_scale) continue;  // held by the stop zone: no way off
        const Clearance k = clearance(m.command);
        if (k.better_than(best_clearance)) {
            best = m;
            best_clearance = k;
            from_navigator = c.v_mps == r.command.v_mps && c.w_radps == r.command.w_radps;
            chosen = c;
        }
    }
    if (from_navigator) {  // nothing keeps more: as decided
        giving_way_.reset();
        return;
    }
    giving_way_ = chosen;
    best.action = MonitorAction::kGiveWay;
    best.recovering = r.recovering;
    r = best;
}

bool CollisionMonitor::recovery_free(const VelocityCommand& c, const VelocityCommand& current,
                                     double duration_s, const std::vector<Eigen::Vector2d>& pts,
                                     const std::vector<char>& dynamic,
                                     const std::vector<double>& age_s) const {
    return first_contact({current, c, duration_s + params_.latency_s, true}, params_.stop_padding_m,
                         pts, dynamic, age_s) < 0.0;
}

}  // namespace makeway::planning

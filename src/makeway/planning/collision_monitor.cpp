#include "makeway/planning/collision_monitor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <unordered_set>

#include "makeway/common/angles.hpp"
#include "makeway/common/floor_index.hpp"
#include "makeway/planning/gap_bridge.hpp"
#include "makeway/planning/param_tables.hpp"

namespace makeway::planning {
namespace {

// Returns of one sweep are thinned to one per cell of this size: the zones' paddings are several
// cells, so nothing the robot could touch is lost, and the memory stays a few thousand points.
constexpr double kThinCell_m = 0.03;

// The pose after following (v, w) for u seconds from the origin (exact arc).
Pose2 along_arc(double v, double w, double u) {
    if (std::abs(w) < 1e-9) return {v * u, 0.0, 0.0};
    const double th = w * u;
    return {v / w * std::sin(th), v / w * (1.0 - std::cos(th)), th};
}

}  // namespace

std::string_view to_string(MonitorAction a) {
    switch (a) {
        case MonitorAction::kNone:
            return "none";
        case MonitorAction::kSlowdown:
            return "slowdown";
        case MonitorAction::kApproach:
            return "approach";
        case MonitorAction::kStop:
            return "stop";
        case MonitorAction::kBackup:
            return "recovery_backup";
        case MonitorAction::kRotate:
            return "recovery_rotate";
        case MonitorAction::kBlocked:
            return "blocked";
        case MonitorAction::kGiveWay:
            return "give_way";
    }
    return "none";
}

std::vector<std::string> CollisionMonitorParams::validate() const {
    std::vector<std::string> p = collision_monitor_table().problems(*this);
    if (!(footprint_length_m > 0.0 && footprint_width_m > 0.0))
        p.push_back("footprint must be positive");
    if (!(body.top_m > body.ground_clearance_m))
        p.push_back("body top must be above its ground clearance");
    if (!(max_acc_mps2 > 0.0 && max_ang_acc_radps2 > 0.0)) p.push_back("accelerations must be > 0");
    if (!(max_v_mps > 0.0 && max_w_radps > 0.0)) p.push_back("top speeds must be > 0");
    if (!(sensor_height_m >= 0.0 && sensor_height_m <= 5.0))
        p.push_back("sensor_height_m must be in [0, 5]");
    return p;
}

void CollisionMonitorParams::apply_robot(const RobotDescription& robot) {
    footprint_length_m = robot.length_m;
    footprint_width_m = robot.width_m;
    body = robot.body();
    max_v_mps = robot.max_v_mps;
    max_w_radps = robot.max_w_radps;
    max_acc_mps2 = robot.max_acc_mps2;
    max_ang_acc_radps2 = robot.max_ang_acc_radps2;
}

CollisionMonitor::CollisionMonitor(const CollisionMonitorParams& params)
    : params_(params), tan_down_(std::tan(-params.lowest_beam_deg * kPi / 180.0)) {
    throw_if_problems(params_.validate(), "collision monitor");
}

std::vector<std::pair<double, Pose2>> CollisionMonitor::trajectory(const Motion& m) const {
    // The unicycle of the simulator and the DWA: each velocity moves toward its target within the
    // acceleration limits, the pose follows the exact arc of each step.
    const double dt = params_.simulation_time_step_s;
    auto approach = [](double x, double target, double step) {
        return x + std::clamp(target - x, -step, step);
    };
    std::vector<std::pair<double, Pose2>> out{{0.0, Pose2{}}};
    double v = m.current.v_mps, w = m.current.w_radps, t = 0.0;
    Pose2 pose;
    for (int i = 0; i < 10000; ++i) {
        const bool commanding = t < m.command_s - 1e-9;
        if (!commanding && (!m.brake || (v == 0.0 && w == 0.0))) break;
        const VelocityCommand target = commanding ? m.command : VelocityCommand{};
        v = approach(v, target.v_mps, params_.max_acc_mps2 * dt);
        w = approach(w, target.w_radps, params_.max_ang_acc_radps2 * dt);
        const Pose2 d = along_arc(v, w, dt);
        const double c = std::cos(pose.yaw_rad), s = std::sin(pose.yaw_rad);
        pose = {pose.x_m + c * d.x_m - s * d.y_m, pose.y_m + s * d.x_m + c * d.y_m,
                wrap_angle(pose.yaw_rad + d.yaw_rad)};
        t += dt;
        out.emplace_back(t, pose);
    }
    return out;
}

double CollisionMonitor::first_contact(const Motion& m, double padding,
                                       const std::vector<Eigen::Vector2d>& pts,
                                       const std::vector<char>& dynamic,
                                       const std::vector<double>& age_s) const {
    const Eigen::Vector2d half = footprint_half();
    const std::vector<std::pair<double, Pose2>> poses = trajectory(m);
    // Only returns the padded footprint can reach along the way.
    const double grow = params_.dynamic_speed_mps, L = params_.latency_s;
    double travel = 0.0;
    for (const auto& [t, q] : poses) travel = std::max(travel, std::hypot(q.x_m, q.y_m));
    const double reach = half.norm() + padding + travel + 1e-9;
    std::vector<Eigen::Vector2d> near;
    std::vector<double> now;     // each return's distance to the footprint where the robot stands
    std::vector<double> growth;  // its padding's growth per second along the way
    std::vector<double> lead;    // the time it has had to move before the check (age + latency)
    for (std::size_t i = 0; i < pts.size(); ++i) {
        const bool moving = !dynamic.empty() && dynamic[i] != 0 && grow > 0.0;
        const double before = L + (i < age_s.size() ? age_s[i] : 0.0);
        const double r = moving ? reach + grow * (before + poses.back().first) : reach;
        if (pts[i].squaredNorm() > r * r) continue;
        near.push_back(pts[i]);
        now.push_back(rect_signed_distance(pts[i], half));
        growth.push_back(moving ? grow : 0.0);
        lead.push_back(before);
    }
    if (static_cast<int>(near.size()) < params_.min_points) return -1.0;
    for (const auto& [t, q] : poses) {
        const double c = std::cos(q.yaw_rad), s = std::sin(q.yaw_rad);
        int hits = 0;
        for (std::size_t j = 0; j < near.size(); ++j) {
            const Eigen::Vector2d d = near[j] - Eigen::Vector2d(q.x_m, q.y_m);
            const double sd =
                rect_signed_distance({c * d.x() + s * d.y(), -s * d.x() + c * d.y()}, half);
            // Inside the zone, and closer than now: a robot may always move away from what is near.
            if (sd <= padding + growth[j] * (lead[j] + t) && sd < now[j] - 1e-4 &&
                ++hits >= params_.min_points)
                return t;
        }
    }
    return -1.0;
}

MonitorResult CollisionMonitor::check(const VelocityCommand& cmd,
                                      const std::vector<Eigen::Vector2d>& pts,
                                      const std::vector<char>& dynamic) const {
    return check(cmd, cmd, pts, dynamic);
}

MonitorResult CollisionMonitor::check(const VelocityCommand& cmd, const VelocityCommand& current,
                                      const std::vector<Eigen::Vector2d>& pts,
                                      const std::vector<char>& dynamic,
                                      const std::vector<double>& age_s) const {
    MonitorResult r;
    r.command = cmd;
    if (!params_.enabled) return r;
    auto hold = [&](MonitorAction a) {
        r.command = {};
        r.scale = 0.0;
        r.action = a;
        return r;
    };
    // Stop: the command for latency_s, then braking, must stay clear. Standing still is always
    // allowed (there is nothing better to do than brake).
    const bool still = cmd.v_mps == 0.0 && cmd.w_radps == 0.0;
    if (still) return r;
    // The nearest walker's return (new, not beside a known chair) to the footprint, for the
    // personal space and the turn cap.
    double walker_m = std::numeric_limits<double>::infinity();
    if (params_.dynamic_personal_space_m > 0.0 || params_.dynamic_turn_space_m > 0.0) {
        for (std::size_t i = 0; i < dynamic.size() && i < pts.size(); ++i) {
            if (dynamic[i] == 1)
                walker_m = std::min(walker_m, rect_signed_distance(pts[i], footprint_half()));
        }
    }
    // Personal space: a mover (a new return: a walker, a chair being pulled) this close to the
    // body holds it, whichever way the command goes. Next to a body, any motion of the robot's
    // surface toward it is a contact the robot caused when the walker steps in (rotating on the
    // spot sweeps a corner; creeping forward closes a gap the walker is about to fill).
    if (params_.dynamic_personal_space_m > 0.0 && walker_m < params_.dynamic_personal_space_m)
        return hold(MonitorAction::kStop);
    // Turning beside a walker: a corner sweeps sideways at w times its reach from the centre, into
    // a walker beside it even while the body as a whole moves away (a walker overtaking the rear
    // corner of a robot turning off its line). Near one, the turn is slowed (the same arc's
    // curvature is not kept: a slower turn is the point) and that command checked instead.
    const double turn_cap = params_.dynamic_turn_max_radps;
    if (params_.dynamic_turn_space_m > 0.0 && walker_m < params_.dynamic_turn_space_m &&
        std::abs(cmd.w_radps) > turn_cap) {
        MonitorResult slower =
            check({cmd.v_mps, std::copysign(turn_cap, cmd.w_radps)}, current, pts, dynamic, age_s);
        if (slower.action == MonitorAction::kNone) slower.action = MonitorAction::kSlowdown;
        return slower;
    }
    if (first_contact({current, cmd, params_.latency_s, true}, params_.stop_padding_m, pts, dynamic,
                      age_s) >= 0.0) {
        return hold(MonitorAction::kStop);
    }
    double scale = 1.0;
    const double T = params_.time_before_collision_s;
    const double t_c = T > 0.0 ? first_contact({current, cmd, T, false}, params_.stop_padding_m,
                                               pts, dynamic, age_s)
                               : -1.0;
    if (t_c >= 0.0 && t_c / T < scale) {  // contact kept at least T away at the scaled speed
        scale = t_c / T;
        r.action = MonitorAction::kApproach;
    }
    const double v = cmd.v_mps, w = cmd.w_radps;
    const double cap =
        params_.slowdown_ratio * std::min(params_.max_v_mps / std::max(std::abs(v), 1e-9),
                                          params_.max_w_radps / std::max(std::abs(w), 1e-9));
    if (cap < scale &&
        first_contact({current, cmd, params_.latency_s + params_.slowdown_time_s, true},
                      params_.slowdown_padding_m, pts) >= 0.0) {
        scale = cap;
        r.action = MonitorAction::kSlowdown;
    }
    if (scale < params_.min_scale) return hold(MonitorAction::kApproach);
    r.scale = scale;
    r.command = {scale * v, scale * w};
    return r;
}

double CollisionMonitor::blind_radius_m(double z_m) const {
    return tan_down_ > 0.0 ? (params_.sensor_height_m - z_m) / tan_down_ : 0.0;
}

MonitorResult CollisionMonitor::filter(const MonitorInput& in) {
    // Forget what the sensor could see again (the new sweep shows it if it is still there), and
    // what is older than blind_memory_s.
    const Eigen::Vector2d here(in.pose.x_m, in.pose.y_m);
    std::erase_if(memory_, [&](const Remembered& m) {
        return m.t_s < in.t_s - params_.blind_memory_s - 1e-9 ||
               (m.p_world - here).norm() >= m.blind_m;
    });
    const Isometry2 T_base_world = to_isometry(in.pose).inverse();
    std::vector<Eigen::Vector2d> pts;
    for (const Remembered& m : memory_) pts.push_back(T_base_world * m.p_world);
    std::vector<char> dynamic(pts.size(), 0);  // remembered returns are where they were
    // The chairs the robot knows of, in the base frame: new returns beside one are the chair
    // moving (someone pulls it), or its thin parts flickering, not a walker.
    std::vector<Polygon2> chairs;
    if (in.chairs_world != nullptr) {
        for (const Polygon2& poly : *in.chairs_world) {
            Polygon2 base;
            for (const Eigen::Vector2d& q : poly) base.push_back(T_base_world * q);
            chairs.push_back(std::move(base));
        }
    }
    auto beside_chair = [&](const Eigen::Vector2d& p_base) {
        return std::any_of(chairs.begin(), chairs.end(), [&](const Polygon2& chair) {
            return convex_distance(chair, p_base) <= params_.personal_space_object_margin_m;
        });
    };
    // The new sweep: the returns the body can hit, thinned; each remembered while the sensor,
    // closing in, could no longer see it.
    if (in.points_world != nullptr) {
        std::unordered_set<std::int64_t> seen;
        std::vector<std::int64_t> cells;
        const double r2 = params_.max_range_m * params_.max_range_m;
        struct Candidate {
            std::size_t index;  ///< into pts
            Eigen::Vector2d q;  ///< world
            double keep_m;      ///< remembered while closer than this to the sensor
            bool high;          ///< high enough to be a mover
            bool seen_before;  ///< a return was near it in the last dynamic_history sweeps (not one
                               ///< sweep's noise)
            bool clustered = false;  ///< near a mover (dynamic_cluster_m)
        };
        std::vector<Candidate> candidates;
        for (const Eigen::Vector3f& p : in.points_world->xyz) {
            if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()) ||
                !params_.body.can_hit(p.z()))
                continue;
            const Eigen::Vector2d q(p.x(), p.y());
            const double d2 = (q - here).squaredNorm();
            if (d2 > r2) continue;
            const auto ix = floor_index(q.x(), kThinCell_m);
            const auto iy = floor_index(q.y(), kThinCell_m);
            if (!seen.insert(cell_key(ix, iy)).second) continue;
            cells.push_back(cell_key(ix, iy));
            pts.push_back(T_base_world * q);
            // New: a return in this cell or next to it in fewer than dynamic_min_seen of the last
            // dynamic_history sweeps (none new before the first). A surface stays where it is
            // sweep after sweep; a walker who turns back crosses each cell it left once. Away
            // from the chairs the robot knows, dynamic_min_seen_off_chairs of them, when larger
            // (a chair's thin parts flicker, and a pulled chair crosses cells it left too); a
            // robot without an object map (no chairs_world) cannot tell them apart and does not.
            const int history = static_cast<int>(previous_cells_.size());
            const int need_near = std::min<int>(params_.dynamic_min_seen, history);
            const int need = in.chairs_world == nullptr
                                 ? need_near
                                 : std::min<int>(std::max(params_.dynamic_min_seen,
                                                          params_.dynamic_min_seen_off_chairs),
                                                 history);
            int seen_in = 0;
            for (const std::vector<std::int64_t>& earlier : previous_cells_) {
                bool here_then = false;
                for (std::int64_t dx = -1; dx <= 1 && !here_then; ++dx) {
                    for (std::int64_t dy = -1; dy <= 1 && !here_then; ++dy)
                        here_then = std::binary_search(earlier.begin(), earlier.end(),
                                                       cell_key(ix + dx, iy + dy));
                }
                if (here_then && ++seen_in >= need) break;
            }
            const bool known =
                seen_in >= need || (seen_in >= need_near && beside_chair(pts.back()));
            const bool seen_before =
                seen_in > 0 || previous_cells_.empty();  // not one sweep's noise
            // Near the floor, noise: the lowest rings graze it ~0.9 m out, and a return 2 cm up
            // there is new in every sweep. People are seen higher up.
            const bool high = p.z() >= params_.dynamic_min_height_m;
            dynamic.push_back(known || !high ? 0 : 1);
            candidates.push_back({pts.size() - 1, q,
                                  std::min(blind_radius_m(p.z()), std::sqrt(d2)) - kThinCell_m,
                                  high, seen_before});
        }
        // A mover stays a mover: returns near one that was new in this sweep or the last
        // dynamic_history sweeps move too (a walker turning back walks into the cells it just
        // left, which are not new).
        std::vector<std::int64_t> movers;
        auto coarse = [&](const Eigen::Vector2d& q) {
            return std::pair<std::int64_t, std::int64_t>(
                floor_index(q.x(), params_.dynamic_cluster_m),
                floor_index(q.y(), params_.dynamic_cluster_m));
        };
        if (params_.dynamic_cluster_m > 0.0) {
            // A mover's cell holds dynamic_cluster_min_new new returns: a walker's leading edge
            // does, the sliver of wall the robot's own motion brings out of a shadow does not.
            std::vector<std::int64_t> seeds;
            for (const Candidate& c : candidates) {
                if (dynamic[c.index])
                    seeds.push_back(cell_key(coarse(c.q).first, coarse(c.q).second));
            }
            std::sort(seeds.begin(), seeds.end());
            for (std::size_t i = 0; i < seeds.size();) {
                std::size_t j = i;
                while (j < seeds.size() && seeds[j] == seeds[i]) ++j;
                if (static_cast<int>(j - i) >= params_.dynamic_cluster_min_new)
                    movers.push_back(seeds[i]);
                i = j;
            }
            for (Candidate& c : candidates) {
                if (dynamic[c.index] || !c.high) continue;
                const auto [cx, cy] = coarse(c.q);
                bool near = false;
                for (std::int64_t dx = -1; dx <= 1 && !near; ++dx) {
                    for (std::int64_t dy = -1; dy <= 1 && !near; ++dy) {
                        const std::int64_t k = cell_key(cx + dx, cy + dy);
                        near = std::binary_search(movers.begin(), movers.end(), k);
                        for (const std::vector<std::int64_t>& earlier : previous_movers_)
                            near = near || std::binary_search(earlier.begin(), earlier.end(), k);
                    }
                }
                dynamic[c.index] = near ? 1 : 0;
                c.clustered = near;
            }
        }
        // Remembered while the sensor, closer than where it was seen, is blind there; returns not
        // seen before (a walker's leading edge, the floor noise at the lowest rings' reach) and a
        // clustered mover's leave no trail. A return seen in one earlier sweep only is new for the
        // zones (dynamic_min_seen) but remembered: what flickers near the robot (a chair's thin
        // parts) must not drop out of the memory it needs in the blind ring.
        // A low edge (a round table's foot, 3 cm high) is in the lowest ring's reach for about one
        // sweep as the robot drives at it: seen once, but as an arc of returns, where the floor's
        // noise gives lone ones.
        auto supported = [&](const Candidate& c) {
            if (params_.low_edge_support <= 0 || c.high) return false;
            const auto ix = floor_index(c.q.x(), kThinCell_m);
            const auto iy = floor_index(c.q.y(), kThinCell_m);
            int n = 0;
            for (std::int64_t dx = -2; dx <= 2; ++dx) {
                for (std::int64_t dy = -2; dy <= 2; ++dy) {
                    if ((dx != 0 || dy != 0) && seen.count(cell_key(ix + dx, iy + dy)) &&
                        ++n >= params_.low_edge_support)
                        return true;
                }
            }
            return false;
        };
        for (const Candidate& c : candidates) {
            if (c.keep_m > 0.0 && (c.seen_before || supported(c)) && !c.clustered)
                memory_.push_back({c.q, in.t_s, c.keep_m});
        }
        std::sort(cells.begin(), cells.end());
        previous_cells_.push_back(std::move(cells));
        previous_movers_.push_back(std::move(movers));
        while (static_cast<int>(previous_cells_.size()) > params_.dynamic_history)
            previous_cells_.pop_front();
        while (static_cast<int>(previous_movers_.size()) > params_.dynamic_history)
            previous_movers_.pop_front();
    }

    // New returns beside a known chair are the chair moving (someone pulls it): still movers for
    // the stop zone, but out of the personal space, the turn cap and the movers' memory, which are
    // for walkers.
    if ((params_.dynamic_personal_space_m > 0.0 || params_.dynamic_memory_s > 0.0 ||
         params_.dynamic_turn_space_m > 0.0) &&
        !chairs.empty()) {
        for (std::size_t i = 0; i < pts.size(); ++i) {
            if (dynamic[i] != 0 && beside_chair(pts[i])) dynamic[i] = 2;
        }
    }

    // Remembered movers: forgotten after dynamic_memory_s, or once new returns are seen within
    // the reach they have had since (the mover, seen again, stands for itself); the others join
    // the returns, flagged, with their age. Of this sweep's movers, a walker's are remembered:
    // near the robot (dynamic_memory_range_m), not beside a known chair, and with at least
    // dynamic_memory_min_new new returns within 0.2 m (a body's edge; a sliver of wall coming out
    // of a shadow as the robot moves is a few).
    std::vector<double> age(pts.size(), 0.0);
    if (params_.dynamic_memory_s > 0.0) {
        std::vector<Eigen::Vector2d> seen_now, walker;
        for (std::size_t i = 0; i < dynamic.size(); ++i) {
            if (dynamic[i] != 0) seen_now.push_back(pts[i]);
        }
        const double range2 = params_.dynamic_memory_range_m * params_.dynamic_memory_range_m;
        for (std::size_t i = 0; i < dynamic.size(); ++i) {
            if (dynamic[i] != 1 || pts[i].squaredNorm() > range2) continue;
            const auto around = std::count_if(
                seen_now.begin(), seen_now.end(),
                [&](const Eigen::Vector2d& s) { return (s - pts[i]).squaredNorm() <= 0.04; });
            if (around >= params_.dynamic_memory_min_new) walker.push_back(pts[i]);
        }
        std::erase_if(movers_, [&](const std::pair<Eigen::Vector2d, double>& m) {
            const double a = in.t_s - m.second;
            if (a > params_.dynamic_memory_s + 1e-9) return true;
            const double r = params_.dynamic_speed_mps * a + kThinCell_m;
            const Eigen::Vector2d q = T_base_world * m.first;
            return std::any_of(seen_now.begin(), seen_now.end(), [&](const Eigen::Vector2d& s) {
                return (s - q).squaredNorm() <= r * r;
            });
        });
        for (const auto& [p, t] : movers_) {
            pts.push_back(T_base_world * p);
            dynamic.push_back(1);
            age.push_back(in.t_s - t);
        }
        const Isometry2 T_world_base = to_isometry(in.pose);
        for (const Eigen::Vector2d& q : walker) movers_.emplace_back(T_world_base * q, in.t_s);
    }

    // Object footprints where the sensor cannot see the floor: their outlines, sampled.
    if (in.footprints_world != nullptr) {
        const double blind = blind_radius_m(params_.body.ground_clearance_m);
        for (const Polygon2& poly : *in.footprints_world) {
            for (std::size_t i = 0; i < poly.size(); ++i) {
                const Eigen::Vector2d a = poly[i], b = poly[(i + 1) % poly.size()];
                const int n =
                    std::max(1, static_cast<int>(std::ceil((b - a).norm() / kThinCell_m)));
                for (int k = 0; k < n; ++k) {
                    const Eigen::Vector2d q = a + (b - a) * (static_cast<double>(k) / n);
                    if ((q - here).norm() >= blind) continue;
                    pts.push_back(T_base_world * q);
                    dynamic.push_back(0);
                    age.push_back(0.0);
                }
            }
        }
    }

    // Narrow gaps between still returns near the robot, closed (the chair seat between its back's
    // posts). Near: what a corner can reach within a second at top speed and the gap beyond it.
    // Never as wide as the footprint: a gap the robot fits through stays open (a narrower robot
    // than the Jackal with the default 0.35 m).
    const double gap_m = std::min(params_.bridge_gap_m, params_.footprint_width_m - kThinCell_m);
    if (gap_m > 0.0) {
        const double near_m =
            0.5 * std::hypot(params_.footprint_length_m, params_.footprint_width_m) +
            params_.max_v_mps + gap_m;
        std::vector<Eigen::Vector2d> still;
        for (std::size_t i = 0; i < pts.size(); ++i) {
            if (dynamic[i] == 0 && pts[i].squaredNorm() <= near_m * near_m) still.push_back(pts[i]);
        }
        for (const Eigen::Vector2d& q : bridge_gaps(still, gap_m, kThinCell_m)) {
            pts.push_back(q);
            dynamic.push_back(0);
            age.push_back(0.0);
        }
    }

    const VelocityCommand current{in.v_mps, in.w_radps};
    MonitorResult r = decide(in, current, pts, dynamic, age);
    if (params_.give_way_horizon_s > 0.0 && in.movers_world != nullptr && !in.movers_world->empty())
        give_way(in, current, pts, dynamic, age, r);
    else
        giving_way_.reset();  // nothing moves: no way off to hold on to
    return r;
}

}  // namespace makeway::planning

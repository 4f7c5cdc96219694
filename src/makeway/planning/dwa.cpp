#include "makeway/planning/dwa.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "makeway/common/angles.hpp"
#include "makeway/planning/param_tables.hpp"

namespace makeway::planning {
namespace {

std::vector<Eigen::Vector2d> footprint_samples(const DwaParams& p, double spacing_m) {
    std::vector<Eigen::Vector2d> out;
    const double length = p.footprint_length_m + 2.0 * p.footprint_padding_m,
                 width = p.footprint_width_m + 2.0 * p.footprint_padding_m;
    const int nx = std::max(2, static_cast<int>(std::ceil(length / spacing_m)) + 1);
    const int ny = std::max(2, static_cast<int>(std::ceil(width / spacing_m)) + 1);
    for (int i = 0; i < nx; ++i) {
        for (int j = 0; j < ny; ++j)
            out.emplace_back(-0.5 * length + length * i / (nx - 1),
                             -0.5 * width + width * j / (ny - 1));
    }
    return out;
}

bool collides(const Costmap& map, const Pose2& pose, const std::vector<Eigen::Vector2d>& samples) {
    const double c = std::cos(pose.yaw_rad), s = std::sin(pose.yaw_rad);
    for (const auto& q : samples) {
        const Eigen::Vector2d p(pose.x_m + c * q.x() - s * q.y(), pose.y_m + s * q.x() + c * q.y());
        const Eigen::Vector2i cell = map.cell_of(p);
        if (!map.inside(cell.x(), cell.y()) || map.at(cell.x(), cell.y()) == cost::kLethal)
            return true;
    }
    return false;
}

Pose2 advance(const Pose2& p, double v, double w, double dt) {
    Pose2 q = p;
    if (std::abs(w) < 1e-9) {
        q.x_m += v * dt * std::cos(p.yaw_rad);
        q.y_m += v * dt * std::sin(p.yaw_rad);
    } else {
        q.x_m += v / w * (std::sin(p.yaw_rad + w * dt) - std::sin(p.yaw_rad));
        q.y_m -= v / w * (std::cos(p.yaw_rad + w * dt) - std::cos(p.yaw_rad));
    }
    q.yaw_rad = wrap_angle(p.yaw_rad + w * dt);
    return q;
}

int soft_cost(const Costmap& map, const Eigen::Vector2d& p) {
    const auto c = map.cost_at(p);
    return c && *c != cost::kUnknown ? std::min<int>(*c, cost::kMaxSoft) : cost::kMaxSoft;
}

// The carrot `lookahead` along the path from the point nearest p, and the highest cost the path
// takes from that point to the carrot.
Eigen::Vector2d carrot(const Costmap& map, const std::vector<Eigen::Vector2d>& path,
                       const Eigen::Vector2d& p, double lookahead, int& envelope) {
    std::size_t nearest = 0;
    for (std::size_t i = 1; i < path.size(); ++i) {
        if ((path[i] - p).squaredNorm() < (path[nearest] - p).squaredNorm()) nearest = i;
    }
    envelope = soft_cost(map, path[nearest]);
    double left = lookahead;
    for (std::size_t i = nearest; i + 1 < path.size(); ++i) {
        const double seg = (path[i + 1] - path[i]).norm();
        if (seg >= left) {
            const Eigen::Vector2d c = path[i] + (path[i + 1] - path[i]) * (left / seg);
            envelope = std::max(envelope, soft_cost(map, c));
            return c;
        }
        envelope = std::max(envelope, soft_cost(map, path[i + 1]));
        left -= seg;
    }
    return path.back();
}

}  // namespace

std::vector<std::string> DwaParams::validate() const {
    std::vector<std::string> out = dwa_table().problems(*this);
    if (!(max_v_mps > 0.0 && min_v_mps <= max_v_mps && min_v_mps >= -max_v_mps))
        out.push_back("need min_v_mps <= max_v_mps, max_v_mps > 0");
    if (!(max_w_radps > 0.0)) out.push_back("max_w_radps must be > 0");
    if (!(acc_v_mps2 > 0.0 && acc_w_radps2 > 0.0)) out.push_back("accelerations must be > 0");
    if (!(control_dt_s > 0.0 && rollout_dt_s > 0.0))
        out.push_back("need rollout_dt_s > 0, control_dt_s > 0");
    if (v_samples < 2 || w_samples < 2 || v_samples * w_samples > 10000)
        out.push_back("v_samples and w_samples must be >= 2 (at most 10000 pairs)");
    if (!(footprint_length_m > 0.0 && footprint_width_m > 0.0))
        out.push_back("footprint must be positive");
    if (!(footprint_padding_m >= 0.0 && footprint_padding_m <= 1.0))
        out.push_back("footprint_padding_m must be in [0, 1]");
    return out;
}

bool footprint_collides(const Costmap& map, const Pose2& pose, const DwaParams& params) {
    return collides(map, pose, footprint_samples(params, 0.5 * map.resolution_m));
}

FootprintChecker::FootprintChecker(const Costmap& map, const DwaParams& p, const GridWindow& window)
    : map_(map),
      samples_(footprint_samples(p, 0.5 * map.resolution_m)),
      half_length_m_(0.5 * p.footprint_length_m + p.footprint_padding_m),
      half_width_m_(0.5 * p.footprint_width_m + p.footprint_padding_m),
      window_(window.clipped(map.width, map.height)) {
    if (window_.empty()) return;
    const int w = window_.x1 - window_.x0, h = window_.y1 - window_.y0;
    lethal_sum_.assign(static_cast<std::size_t>(w + 1) * (h + 1), 0);
    for (int j = 0; j < h; ++j) {
        int row = 0;
        for (int i = 0; i < w; ++i) {
            row += map.at(window_.x0 + i, window_.y0 + j) == cost::kLethal;
            lethal_sum_[static_cast<std::size_t>(j + 1) * (w + 1) + (i + 1)] =
                lethal_sum_[static_cast<std::size_t>(j) * (w + 1) + (i + 1)] + row;
        }
    }
}

bool FootprintChecker::collides(const Pose2& pose) const {
    if (!window_.empty()) {
        // Every sample lies in the footprint's bounding box, so every sample's cell lies in the
        // box's cell range (a micrometre wider, for the rounding of the rotated samples).
        const double c = std::abs(std::cos(pose.yaw_rad)), s = std::abs(std::sin(pose.yaw_rad));
        const double hx = c * half_length_m_ + s * half_width_m_ + 1e-6,
                     hy = s * half_length_m_ + c * half_width_m_ + 1e-6;
        const Eigen::Vector2i lo = map_.cell_of({pose.x_m - hx, pose.y_m - hy});
        const Eigen::Vector2i hi = map_.cell_of({pose.x_m + hx, pose.y_m + hy});
        if (lo.x() >= window_.x0 && lo.y() >= window_.y0 && hi.x() < window_.x1 &&
            hi.y() < window_.y1) {
            const int w = window_.x1 - window_.x0;
            const auto at = [&](int i, int j) {
                return lethal_sum_[static_cast<std::size_t>(j - window_.y0) * (w + 1) +
                                   (i - window_.x0)];
            };
            const int lethal = at(hi.x() + 1, hi.y() + 1) - at(lo.x(), hi.y() + 1) -
                               at(hi.x() + 1, lo.y()) + at(lo.x(), lo.y());
            if (lethal == 0) return false;
        }
    }
    return makeway::planning::collides(map_, pose, samples_);
}

DwaResult dwa_step(const Costmap& map, const DwaState& st, const std::vector<Eigen::Vector2d>& path,
                   const DwaParams& p) {
    DwaResult result;
    if (path.empty()) return result;
    int envelope = 0;
    const Eigen::Vector2d goal =
        carrot(map, path, {st.pose.x_m, st.pose.y_m}, p.lookahead_m, envelope);
    // Where the robot stands is inside the envelope too: it may always leave the way it came.
    envelope = std::max(envelope, soft_cost(map, {st.pose.x_m, st.pose.y_m})) +
               static_cast<int>(p.envelope_margin);
    const double v_lo = std::max(p.min_v_mps, st.v_mps - p.acc_v_mps2 * p.control_dt_s);
    const double v_hi = std::min(p.max_v_mps, st.v_mps + p.acc_v_mps2 * p.control_dt_s);
    const double w_lo = std::max(-p.max_w_radps, st.w_radps - p.acc_w_radps2 * p.control_dt_s);
    const double w_hi = std::min(p.max_w_radps, st.w_radps + p.acc_w_radps2 * p.control_dt_s);
    const int steps = static_cast<int>(std::lround(p.horizon_s / p.rollout_dt_s));
    // Every rollout stays within the fastest sample's reach of the robot, its footprint within that
    // plus the footprint's half diagonal.
    const double reach_m = std::max(std::abs(v_lo), std::abs(v_hi)) * steps * p.rollout_dt_s +
                           std::hypot(0.5 * p.footprint_length_m + p.footprint_padding_m,
                                      0.5 * p.footprint_width_m + p.footprint_padding_m);
    const Eigen::Vector2i centre = map.cell_of({st.pose.x_m, st.pose.y_m});
    const int reach = static_cast<int>(std::ceil(reach_m / map.resolution_m)) + 2;
    const FootprintChecker checker(
        map, p,
        {centre.x() - reach, centre.y() - reach, centre.x() + reach + 1, centre.y() + reach + 1});

    struct Candidate {
        double v, w, path, heading, clearance, speed, excess;
        std::vector<Pose2> rollout;
    };
    std::vector<Candidate> admissible;
    for (int i = 0; i < p.v_samples; ++i) {
        const double v = v_lo + (v_hi - v_lo) * i / (p.v_samples - 1);
        for (int j = 0; j < p.w_samples; ++j) {
            const double w = w_lo + (w_hi - w_lo) * j / (p.w_samples - 1);
            ++result.samples;
            Candidate c{v, w, 0, 0, 0, 0, 0, {}};
            Pose2 pose = st.pose;
            bool hit = false;
            double cost_sum = 0.0;
            for (int k = 0; k < steps && !hit; ++k) {
                pose = advance(pose, v, w, p.rollout_dt_s);
                hit = checker.collides(pose);
                const int centre_cost = soft_cost(map, {pose.x_m, pose.y_m});
                cost_sum += centre_cost;
                c.excess += std::max(0, centre_cost - envelope);
                c.rollout.push_back(pose);
            }
            if (hit) continue;  // never choose a velocity that collides within the horizon
            const Eigen::Vector2d end(pose.x_m, pose.y_m);
            c.path = -(goal - end).norm();
            c.heading = -std::abs(
                angle_diff(std::atan2(goal.y() - end.y(), goal.x() - end.x()), pose.yaw_rad));
            c.clearance = -cost_sum / (steps * cost::kMaxSoft);
            c.speed = v / p.max_v_mps;
            admissible.push_back(std::move(c));
        }
    }
    result.admissible = static_cast<int>(admissible.size());
    if (admissible.empty()) return result;
    if (p.plan_envelope) {  // only the rollouts that leave the plan's envelope least
        double least = std::numeric_limits<double>::infinity();
        for (const auto& c : admissible) least = std::min(least, c.excess);
        std::erase_if(admissible, [&](const Candidate& c) { return c.excess > least; });
    }
    auto normalise = [&](double Candidate::*term) {
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (const auto& c : admissible) lo = std::min(lo, c.*term), hi = std::max(hi, c.*term);
        for (auto& c : admissible) c.*term = hi > lo ? (c.*term - lo) / (hi - lo) : 0.0;
    };
    normalise(&Candidate::path);
    normalise(&Candidate::heading);
    normalise(&Candidate::clearance);
    normalise(&Candidate::speed);
    const Candidate* best = nullptr;
    double best_score = -std::numeric_limits<double>::infinity();
    for (const auto& c : admissible) {
        const double score = p.w_path * c.path + p.w_heading * c.heading +
                             p.w_clearance * c.clearance + p.w_speed * c.speed;
        if (score > best_score) best_score = score, best = &c;
    }
    result.found = true;
    result.command = {best->v, best->w};
    result.best_rollout = best->rollout;
    return result;
}

}  // namespace makeway::planning

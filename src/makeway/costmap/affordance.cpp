#include "makeway/costmap/affordance.hpp"

#include <algorithm>
#include <cmath>

#include "makeway/costmap/param_tables.hpp"

namespace makeway::costmap {
namespace {

Eigen::Vector2d to_object_frame(const ObjectEstimate& o, const Eigen::Vector2d& p) {
    const Eigen::Vector2d d = p - o.box_world.centre_m.head<2>();
    const double c = std::cos(o.box_world.yaw_rad), s = std::sin(o.box_world.yaw_rad);
    return {c * d.x() + s * d.y(), -s * d.x() + c * d.y()};
}

// Half extents of the zone in the object frame.
Eigen::Vector2d zone_half_extent(const ObjectEstimate& o, const AffordanceParams& p) {
    const double hl = 0.5 * o.box_world.size_m.x(), hw = 0.5 * o.box_world.size_m.y();
    if (o.cls == ObjectClass::kChair) return {hl + p.chair.forward_back_m, hw + p.chair.side_m};
    const bool square =
        std::abs(o.box_world.size_m.x() - o.box_world.size_m.y()) < p.table.square_tolerance_m;
    return {hl + (square ? p.table.sides_m : p.table.ends_m), hw + p.table.sides_m};
}

// The paper's zone coordinate, q in the object frame.
double hand_drawn_coordinate(const ObjectEstimate& o, const AffordanceParams& p,
                             const Eigen::Vector2d& q_object) {
    const Eigen::Vector2d q = q_object.cwiseAbs();
    const Eigen::Vector2d half_object = 0.5 * o.box_world.size_m.head<2>();
    if ((q.array() <= half_object.array()).all()) return 0.0;
    const Eigen::Vector2d half_zone = zone_half_extent(o, p);
    if (o.cls == ObjectClass::kChair) {
        // Ellipse through the zone extents; u grows from the chair's inscribed ellipse outward.
        const double e = std::hypot(q.x() / half_zone.x(), q.y() / half_zone.y());
        const double e0 =
            std::min(half_object.x() / half_zone.x(), half_object.y() / half_zone.y());
        return std::max(0.0, (e - e0) / std::max(1e-9, 1.0 - e0));
    }
    // Rectangle: the larger of the normalised overshoots beyond the table edge on each axis.
    const Eigen::Vector2d pad = half_zone - half_object;
    const double ux =
        q.x() <= half_object.x() ? 0.0 : (q.x() - half_object.x()) / std::max(pad.x(), 1e-9);
    const double uy =
        q.y() <= half_object.y() ? 0.0 : (q.y() - half_object.y()) / std::max(pad.y(), 1e-9);
    return std::max(ux, uy);
}

// Distance [m] from q (object frame, outside the zone) to the hand-drawn zone's boundary: exact for
// a table's rectangle, to first order for a chair's ellipse ((e - 1) / |grad e|, within a few per
// cent over a margin of a few decimetres).
double hand_drawn_distance_outside(const ObjectEstimate& o, const AffordanceParams& p,
                                   const Eigen::Vector2d& q_object) {
    const Eigen::Vector2d q = q_object.cwiseAbs();
    const Eigen::Vector2d h = zone_half_extent(o, p);
    if (o.cls == ObjectClass::kChair) {
        const double ax = std::max(h.x(), 1e-9), ay = std::max(h.y(), 1e-9);
        const double e = std::hypot(q.x() / ax, q.y() / ay);
        const double grad = std::hypot(q.x() / (ax * ax), q.y() / (ay * ay)) / std::max(e, 1e-9);
        return std::max(0.0, (e - 1.0) / std::max(grad, 1e-9));
    }
    return std::hypot(std::max(0.0, q.x() - h.x()), std::max(0.0, q.y() - h.y()));
}

const ClassZone* learned_zone_of(const ObjectEstimate& o, const AffordanceParams& p) {
    return p.learned ? p.learned->of(o.cls) : nullptr;
}

}  // namespace

std::vector<std::string> AffordanceParams::validate() const {
    std::vector<std::string> out = affordance_table().problems(*this);
    if (learned) {
        for (const std::string& m : learned->validate()) out.push_back("zones: " + m);
    }
    return out;
}

namespace {

// zone_coordinate of q, in the object frame.
double coordinate_in_object_frame(const ObjectEstimate& o, const AffordanceParams& p,
                                  const Eigen::Vector2d& q) {
    const ClassZone* zone = learned_zone_of(o, p);
    if (zone == nullptr) return hand_drawn_coordinate(o, p, q);
    const Eigen::Vector2d half_object = 0.5 * o.box_world.size_m.head<2>();
    if ((q.cwiseAbs().array() <= half_object.array()).all()) return 0.0;
    // learned_zone.hpp: the blend of the learned coverage and the hand-drawn zone's.
    const LearnedZones& l = *p.learned;
    const double n = zone->observations, n0 = l.prior_strength, tau = l.coverage_threshold;
    const double u_prior = hand_drawn_coordinate(o, p, q);
    if (n <= 0.0) return u_prior;  // nothing learned: the paper's zone, to the bit
    // u = ln c / ln tau: coverages span decades (a chair goes 0.5 m back one time in three, 1 m
    // one time in thirty), so costs follow their logarithm; the prior's coverage is tau^u.
    const double c_prior = u_prior <= 1.0 ? std::pow(tau, u_prior) : 0.0;
    const double c_learned = l.coverage(o.cls, half_object, q);
    const double c = (n * c_learned + n0 * c_prior) / (n + n0);
    return c >= 1.0 ? 0.0 : c <= 0.0 ? 2.0 : std::log(c) / std::log(tau);
}

}  // namespace

double zone_coordinate(const ObjectEstimate& o, const AffordanceParams& p,
                       const Eigen::Vector2d& p_m) {
    return coordinate_in_object_frame(o, p, to_object_frame(o, p_m));
}

std::uint8_t zone_cost(const ObjectEstimate& o, const AffordanceParams& p,
                       const Eigen::Vector2d& p_m) {
    if (o.existence < p.min_existence) return cost::kFree;
    const Eigen::Vector2d q = to_object_frame(o, p_m);
    const double u = coordinate_in_object_frame(o, p, q);
    if (u > 1.0) {
        const ClassZone* zone = learned_zone_of(o, p);  // one that learned something: no margin
        if (p.margin_m <= 0.0 || (zone != nullptr && zone->observations > 0.0)) return cost::kFree;
        const double d = hand_drawn_distance_outside(o, p, q);
        if (d >= p.margin_m) return cost::kFree;
        return static_cast<std::uint8_t>(
            std::clamp(std::lround(p.margin_cost * (1.0 - d / p.margin_m)), 1L,
                       static_cast<long>(cost::kMaxSoft)));
    }
    const double peak = o.cls == ObjectClass::kChair ? p.chair.peak_cost : p.table.peak_cost;
    const double edge = o.cls == ObjectClass::kChair ? p.chair.edge_cost : p.table.edge_cost;
    return static_cast<std::uint8_t>(
        std::clamp(std::lround(peak + (edge - peak) * u), 1L, static_cast<long>(cost::kMaxSoft)));
}

void zone_bounds(const ObjectEstimate& o, const AffordanceParams& p, Eigen::Vector2d& min_m,
                 Eigen::Vector2d& max_m) {
    const Eigen::Vector2d h = zone_half_extent(o, p);
    const double c = std::abs(std::cos(o.box_world.yaw_rad)),
                 s = std::abs(std::sin(o.box_world.yaw_rad));
    Eigen::Vector2d r(c * h.x() + s * h.y(), s * h.x() + c * h.y());
    if (const ClassZone* zone = learned_zone_of(o, p)) {
        // The learned coverage vanishes beyond its reach (a circle); the prior's rectangle
        // stands while it has weight.
        const double reach =
            learned_reach_m(*zone, p.learned->kernel_m, 0.5 * o.box_world.size_m.head<2>());
        const Eigen::Vector2d circle(reach, reach);
        r = p.learned->prior_strength > 0.0 ? r.cwiseMax(circle) : circle;
    }
    min_m = o.box_world.centre_m.head<2>() - r;
    max_m = o.box_world.centre_m.head<2>() + r;
}

std::vector<Eigen::Vector2d> zone_outline(const ObjectEstimate& object,
                                          const AffordanceParams& params, int rays) {
    std::vector<Eigen::Vector2d> out;
    const Eigen::Vector2d c = object.box_world.centre_m.head<2>();
    for (int k = 0; k < rays; ++k) {
        const double a = 2.0 * M_PI * k / rays;
        const Eigen::Vector2d d(std::cos(a), std::sin(a));
        double r = 0.0;
        while (r < 6.0 && in_affordance_zone(object, params, c + (r + 0.01) * d)) r += 0.01;
        out.push_back(c + r * d);
    }
    return out;
}

}  // namespace makeway::costmap

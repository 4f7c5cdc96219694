#include "makeway/sim/furniture.hpp"

#include <array>
#include <cmath>

#include "makeway/common/angles.hpp"
#include "makeway/common/random.hpp"
#include "makeway/sim/mesh_primitives.hpp"

namespace makeway::sim {
namespace {

using V3 = Eigen::Vector3d;

constexpr std::array<std::string_view, kNumFurnitureStyles> kNames{
    "four_leg_chair", "office_chair",     "stool",          "armchair",   "rect_table",
    "round_table",    "conference_table", "stacking_chair", "sled_chair", "cantilever_chair",
    "bar_stool",      "folding_chair",    "bench",          "sofa",       "lounge_chair",
    "pedestal_table", "coffee_table",     "balcony_table",  "desk",       "folding_table",
    "side_table"};
constexpr std::array<ObjectClass, kNumFurnitureStyles> kClasses{
    ObjectClass::kChair, ObjectClass::kChair, ObjectClass::kChair, ObjectClass::kChair,
    ObjectClass::kTable, ObjectClass::kTable, ObjectClass::kTable, ObjectClass::kChair,
    ObjectClass::kChair, ObjectClass::kChair, ObjectClass::kChair, ObjectClass::kChair,
    ObjectClass::kChair, ObjectClass::kChair, ObjectClass::kChair, ObjectClass::kTable,
    ObjectClass::kTable, ObjectClass::kTable, ObjectClass::kTable, ObjectClass::kTable,
    ObjectClass::kTable};

// Four legs at the corners of a rectangle inset from the given half extents.
void add_four_legs(TriangleMesh& m, double half_x, double half_y, double height, double leg) {
    for (double sx : {-1.0, 1.0}) {
        for (double sy : {-1.0, 1.0}) {
            add_box(m, V3(sx * (half_x - leg / 2), sy * (half_y - leg / 2), height / 2),
                    V3(leg, leg, height));
        }
    }
}

void four_leg_chair(TriangleMesh& m, Rng& rng) {
    const double w = uniform(rng, 0.40, 0.48), d = uniform(rng, 0.40, 0.47);
    const double seat_h = uniform(rng, 0.43, 0.48), top_h = uniform(rng, 0.78, 0.92);
    const double leg = uniform(rng, 0.025, 0.035), seat_t = uniform(rng, 0.03, 0.05);
    add_four_legs(m, d / 2, w / 2, seat_h - seat_t, leg);
    add_box(m, V3(0, 0, seat_h - seat_t / 2), V3(d, w, seat_t));
    // Back posts continue the rear legs; a backrest panel spans them.
    const double back_t = uniform(rng, 0.02, 0.035);
    for (double sy : {-1.0, 1.0}) {
        add_box(m, V3(-d / 2 + leg / 2, sy * (w / 2 - leg / 2), (seat_h + top_h) / 2),
                V3(leg, leg, top_h - seat_h));
    }
    const double panel_lo = seat_h + uniform(rng, 0.12, 0.2);
    add_box(m, V3(-d / 2 + back_t / 2, 0, (panel_lo + top_h) / 2), V3(back_t, w, top_h - panel_lo));
}

void office_chair(TriangleMesh& m, Rng& rng) {
    const double star_r = uniform(rng, 0.30, 0.34), seat_h = uniform(rng, 0.42, 0.52);
    const double seat_w = uniform(rng, 0.46, 0.52), seat_d = uniform(rng, 0.44, 0.50);
    const double seat_t = uniform(rng, 0.06, 0.08);
    const double phase = uniform(rng, 0.0, 2.0 * kPi / 5.0);
    for (int i = 0; i < 5; ++i) {
        const double a = phase + 2.0 * kPi * i / 5.0;
        const V3 tip(star_r * std::cos(a), star_r * std::sin(a), 0.07);
        add_strut(m, V3(0, 0, 0.09), tip, 0.04);
        add_box(m, V3(tip.x(), tip.y(), 0.03), V3(0.05, 0.05, 0.06), a);  // caster
    }
    add_cylinder(m, V3(0, 0, 0.09), uniform(rng, 0.025, 0.035), seat_h - seat_t - 0.09, 12);
    add_box(m, V3(0, 0, seat_h - seat_t / 2), V3(seat_d, seat_w, seat_t));
    const double back_lo = seat_h + uniform(rng, 0.08, 0.14),
                 back_hi = back_lo + uniform(rng, 0.40, 0.55);
    const double back_t = uniform(rng, 0.05, 0.08);
    add_box(m, V3(-seat_d / 2 - 0.02, 0, (back_lo + back_hi) / 2),
            V3(back_t, uniform(rng, 0.40, 0.48), back_hi - back_lo));
    add_strut(m, V3(-seat_d / 2 + 0.05, 0, seat_h - seat_t),
              V3(-seat_d / 2 - 0.02, 0, back_lo + 0.05), 0.04);
    if (bernoulli(rng, 0.6)) {  // armrests
        const double arm_h = seat_h + uniform(rng, 0.18, 0.24);
        for (double sy : {-1.0, 1.0}) {
            const double y = sy * (seat_w / 2 + 0.02);
            add_box(m, V3(0, y, arm_h), V3(0.26, 0.06, 0.03));
            add_strut(m, V3(-0.05, y, seat_h - seat_t / 2), V3(-0.05, y, arm_h), 0.025);
        }
    }
}

void stool(TriangleMesh& m, Rng& rng) {
    const double r = uniform(rng, 0.15, 0.20), h = uniform(rng, 0.45, 0.75);
    const double seat_t = uniform(rng, 0.03, 0.05), splay = uniform(rng, 0.02, 0.06);
    add_cylinder(m, V3(0, 0, h - seat_t), r, seat_t, 24);
    const int legs = bernoulli(rng, 0.5) ? 3 : 4;
    for (int i = 0; i < legs; ++i) {
        const double a = 2.0 * kPi * i / legs + kPi / 4;
        const V3 dir(std::cos(a), std::sin(a), 0);
        add_strut(m, (r - 0.03) * dir + V3(0, 0, h - seat_t), (r - 0.03 + splay) * dir, 0.03);
    }
}

void armchair(TriangleMesh& m, Rng& rng) {
    const double w = uniform(rng, 0.70, 0.90), d = uniform(rng, 0.70, 0.85);
    const double seat_h = uniform(rng, 0.40, 0.45), arm_h = uniform(rng, 0.55, 0.65);
    const double back_h = uniform(rng, 0.75, 0.95), back_d = uniform(rng, 0.15, 0.22);
    const double arm_w = uniform(rng, 0.12, 0.18), foot = 0.06;
    add_four_legs(m, d / 2, w / 2, foot, 0.05);
    add_box(m, V3(0, 0, (foot + seat_h) / 2), V3(d, w, seat_h - foot));
    add_box(m, V3(-d / 2 + back_d / 2, 0, (seat_h + back_h) / 2), V3(back_d, w, back_h - seat_h));
    for (double sy : {-1.0, 1.0}) {
        add_box(m, V3(back_d / 2, sy * (w / 2 - arm_w / 2), (seat_h + arm_h) / 2),
                V3(d - back_d, arm_w, arm_h - seat_h));
    }
}

void rect_table(TriangleMesh& m, Rng& rng, double l_lo, double l_hi, double w_lo, double w_hi) {
    const double l = uniform(rng, l_lo, l_hi), w = uniform(rng, w_lo, w_hi);
    const double h = uniform(rng, 0.72, 0.76), top_t = uniform(rng, 0.025, 0.04);
    const double leg = uniform(rng, 0.04, 0.06), inset = uniform(rng, 0.03, 0.08);
    add_box(m, V3(0, 0, h - top_t / 2), V3(l, w, top_t));
    add_four_legs(m, l / 2 - inset, w / 2 - inset, h - top_t, leg);
    add_box(m, V3(0, w / 2 - inset - leg / 2, h - top_t - 0.05),
            V3(l - 2 * inset, 0.02, 0.1));  // apron
    add_box(m, V3(0, -(w / 2 - inset - leg / 2), h - top_t - 0.05), V3(l - 2 * inset, 0.02, 0.1));
}

void round_table(TriangleMesh& m, Rng& rng) {
    const double r = uniform(rng, 0.40, 0.60), h = uniform(rng, 0.72, 0.76);
    const double top_t = uniform(rng, 0.025, 0.04);
    add_cylinder(m, V3(0, 0, h - top_t), r, top_t, 32);
    add_cylinder(m, V3(0, 0, 0.03), uniform(rng, 0.04, 0.06), h - top_t - 0.03, 12);
    add_cylinder(m, V3(0, 0, 0), uniform(rng, 0.25, 0.30), 0.03, 24);
}

void conference_table(TriangleMesh& m, Rng& rng) {
    const double l = uniform(rng, 2.4, 3.6), w = uniform(rng, 1.0, 1.4);
    const double h = uniform(rng, 0.72, 0.76), top_t = uniform(rng, 0.03, 0.05);
    add_box(m, V3(0, 0, h - top_t / 2), V3(l, w, top_t));
    for (double sx : {-1.0, 1.0}) {  // two panel legs
        add_box(m, V3(sx * (l / 2 - 0.3), 0, (h - top_t) / 2), V3(0.05, 0.8 * w, h - top_t));
    }
    add_box(m, V3(0, 0, h - top_t - 0.2), V3(l - 0.6, 0.03, 0.3));  // modesty panel
}

// A seat and a back rest, the back at -x (the chair faces +x).
void seat_and_back(TriangleMesh& m, double d, double w, double seat_h, double seat_t, double top_h,
                   double back_t, double tilt = 0.0) {
    add_box(m, V3(0, 0, seat_h - seat_t / 2), V3(d, w, seat_t));
    const double lo = seat_h + 0.05;
    if (tilt == 0.0) {
        add_box(m, V3(-d / 2 + back_t / 2, 0, (lo + top_h) / 2), V3(back_t, w, top_h - lo));
        return;
    }
    // A reclined back as a stack of slabs stepping backwards.
    const int steps = 6;
    for (int i = 0; i < steps; ++i) {
        const double z0 = lo + (top_h - lo) * i / steps, z1 = lo + (top_h - lo) * (i + 1) / steps;
        add_box(m, V3(-d / 2 + back_t / 2 - tilt * (0.5 * (z0 + z1) - lo), 0, 0.5 * (z0 + z1)),
                V3(back_t, w, z1 - z0));
    }
}

void stacking_chair(TriangleMesh& m, Rng& rng) {
    const double w = uniform(rng, 0.42, 0.50), d = uniform(rng, 0.42, 0.50),
                 seat_h = uniform(rng, 0.44, 0.47);
    const double tube = uniform(rng, 0.018, 0.025), splay = uniform(rng, 0.03, 0.06);
    for (double sx : {-1.0, 1.0}) {
        for (double sy : {-1.0, 1.0}) {
            add_strut(m, V3(sx * (d / 2 - 0.03), sy * (w / 2 - 0.03), seat_h - 0.02),
                      V3(sx * (d / 2 - 0.03 + splay), sy * (w / 2 - 0.03 + splay), 0), tube);
        }
    }
    seat_and_back(m, d, w, seat_h, 0.02, uniform(rng, 0.80, 0.86), 0.015, uniform(rng, 0.05, 0.15));
}

void sled_chair(TriangleMesh& m, Rng& rng) {
    const double w = uniform(rng, 0.44, 0.52), d = uniform(rng, 0.45, 0.52),
                 seat_h = uniform(rng, 0.44, 0.47);
    const double tube = uniform(rng, 0.018, 0.022);
    for (double sy : {-1.0, 1.0}) {
        const double y = sy * (w / 2 - 0.02);
        add_strut(m, V3(-d / 2, y, tube / 2), V3(d / 2 + 0.03, y, tube / 2),
                  tube);  // the runner on the floor
        add_strut(m, V3(d / 2 + 0.03, y, tube / 2), V3(d / 2 - 0.04, y, seat_h - 0.02), tube);
        add_strut(m, V3(-d / 2, y, tube / 2), V3(-d / 2 + 0.04, y, seat_h - 0.02), tube);
    }
    seat_and_back(m, d, w, seat_h, 0.025, uniform(rng, 0.80, 0.88), 0.02, uniform(rng, 0.0, 0.1));
}

void cantilever_chair(TriangleMesh& m, Rng& rng) {
    const double w = uniform(rng, 0.45, 0.52), d = uniform(rng, 0.45, 0.52),
                 seat_h = uniform(rng, 0.44, 0.48);
    const double tube = uniform(rng, 0.022, 0.028);
    for (double sy : {-1.0, 1.0}) {
        const double y = sy * (w / 2 - 0.02);
        add_strut(m, V3(-d / 2 + 0.05, y, tube / 2), V3(d / 2 + 0.02, y, tube / 2),
                  tube);  // on the floor
        add_strut(m, V3(d / 2 + 0.02, y, tube / 2), V3(d / 2 - 0.02, y, seat_h - 0.03),
                  tube);  // the cantilever
    }
    add_strut(m, V3(-d / 2 + 0.05, -(w / 2 - 0.02), tube / 2),
              V3(-d / 2 + 0.05, w / 2 - 0.02, tube / 2), tube);
    seat_and_back(m, d, w, seat_h, 0.03, uniform(rng, 0.80, 0.90), 0.025);
}

void bar_stool(TriangleMesh& m, Rng& rng) {
    const double h = uniform(rng, 0.65, 0.80), r = uniform(rng, 0.17, 0.21);
    add_cylinder(m, V3(0, 0, 0), uniform(rng, 0.20, 0.24), 0.02, 24);  // base plate
    add_cylinder(m, V3(0, 0, 0.02), 0.03, h - 0.08, 12);               // column
    add_cylinder(m, V3(0, 0, h - 0.06), r, 0.06, 24);                  // seat
    const double ring_h = uniform(rng, 0.25, 0.32), ring_r = uniform(rng, 0.18, 0.22);
    for (int i = 0; i < 8; ++i) {  // foot ring
        const double a0 = 2 * kPi * i / 8, a1 = 2 * kPi * (i + 1) / 8;
        add_strut(m, V3(ring_r * std::cos(a0), ring_r * std::sin(a0), ring_h),
                  V3(ring_r * std::cos(a1), ring_r * std::sin(a1), ring_h), 0.015);
    }
    if (bernoulli(rng, 0.5))
        add_box(m, V3(-r + 0.02, 0, h + 0.15), V3(0.03, 0.3, 0.25));  // a low back
}

void folding_chair(TriangleMesh& m, Rng& rng) {
    const double w = uniform(rng, 0.42, 0.46), d = uniform(rng, 0.40, 0.45),
                 seat_h = uniform(rng, 0.44, 0.47);
    const double tube = 0.02;
    for (double sy : {-1.0, 1.0}) {  // the X of the side frames
        const double y = sy * (w / 2 - 0.01);
        add_strut(m, V3(-d / 2 - 0.05, y, 0), V3(d / 2, y, seat_h), tube);
        add_strut(m, V3(d / 2 + 0.02, y, 0), V3(-d / 2, y, seat_h + 0.35), tube);
    }
    add_box(m, V3(0, 0, seat_h - 0.01), V3(d, w, 0.02));
    add_box(m, V3(-d / 2 + 0.03, 0, seat_h + 0.28), V3(0.02, w, 0.16));
}

void bench(TriangleMesh& m, Rng& rng) {
    const double l = uniform(rng, 1.2, 1.8), d = uniform(rng, 0.32, 0.42),
                 h = uniform(rng, 0.43, 0.47);
    add_box(m, V3(0, 0, h - 0.02), V3(d, l, 0.04));  // a bench faces +x: its length runs along y
    for (double sy : {-1.0, 1.0})
        add_box(m, V3(0, sy * (l / 2 - 0.12), (h - 0.04) / 2), V3(d - 0.04, 0.04, h - 0.04));
    if (bernoulli(rng, 0.5)) add_box(m, V3(-d / 2 + 0.02, 0, h + 0.2), V3(0.03, l, 0.25));
}

void sofa(TriangleMesh& m, Rng& rng) {
    const double w = uniform(rng, 1.5, 2.2), d = uniform(rng, 0.80, 0.95),
                 seat_h = uniform(rng, 0.40, 0.45);
    const double back_h = uniform(rng, 0.75, 0.90), arm_w = uniform(rng, 0.12, 0.22),
                 back_d = uniform(rng, 0.18, 0.25);
    add_four_legs(m, d / 2 - 0.03, w / 2 - 0.03, 0.08, 0.05);
    add_box(m, V3(0, 0, (0.08 + seat_h) / 2), V3(d, w, seat_h - 0.08));
    add_box(m, V3(-d / 2 + back_d / 2, 0, (seat_h + back_h) / 2), V3(back_d, w, back_h - seat_h));
    const double arm_h = uniform(rng, 0.58, 0.68);
    for (double sy : {-1.0, 1.0})
        add_box(m, V3(back_d / 2, sy * (w / 2 - arm_w / 2), (seat_h + arm_h) / 2),
                V3(d - back_d, arm_w, arm_h - seat_h));
}

void lounge_chair(TriangleMesh& m, Rng& rng) {
    const double w = uniform(rng, 0.65, 0.80), d = uniform(rng, 0.75, 0.90),
                 seat_h = uniform(rng, 0.33, 0.40);
    add_four_legs(m, d / 2 - 0.04, w / 2 - 0.04, seat_h - 0.08, 0.035);
    seat_and_back(m, d, w, seat_h, 0.08, uniform(rng, 0.80, 0.95), 0.08, uniform(rng, 0.3, 0.45));
}

void pedestal_table(TriangleMesh& m, Rng& rng) {
    const double h = uniform(rng, 0.72, 0.76), top_t = uniform(rng, 0.02, 0.035);
    if (bernoulli(rng, 0.5)) {
        add_cylinder(m, V3(0, 0, h - top_t), uniform(rng, 0.30, 0.40), top_t, 32);
    } else {
        const double a = uniform(rng, 0.60, 0.75);
        add_box(m, V3(0, 0, h - top_t / 2), V3(a, a, top_t));
    }
    add_cylinder(m, V3(0, 0, 0.03), uniform(rng, 0.03, 0.045), h - top_t - 0.03, 12);
    const double foot = uniform(rng, 0.22, 0.30);
    add_box(m, V3(0, 0, 0.015), V3(2 * foot, 0.05, 0.03));
    add_box(m, V3(0, 0, 0.015), V3(0.05, 2 * foot, 0.03));
}

void coffee_table(TriangleMesh& m, Rng& rng) {
    const double l = uniform(rng, 0.9, 1.3), w = uniform(rng, 0.5, 0.7),
                 h = uniform(rng, 0.35, 0.45);
    add_box(m, V3(0, 0, h - 0.02), V3(l, w, 0.04));
    add_four_legs(m, l / 2 - 0.04, w / 2 - 0.04, h - 0.04, 0.05);
    if (bernoulli(rng, 0.5)) add_box(m, V3(0, 0, 0.12), V3(l - 0.1, w - 0.1, 0.02));  // a shelf
}

void balcony_table(TriangleMesh& m, Rng& rng) {
    const double r = uniform(rng, 0.28, 0.35), h = uniform(rng, 0.70, 0.74);
    add_cylinder(m, V3(0, 0, h - 0.02), r, 0.02, 32);
    for (int i = 0; i < 3; ++i) {
        const double a = 2 * kPi * i / 3;
        const V3 dir(std::cos(a), std::sin(a), 0);
        add_strut(m, 0.6 * r * dir + V3(0, 0, h - 0.02), (r + 0.03) * dir, 0.018);
    }
}

void desk(TriangleMesh& m, Rng& rng) {
    const double l = uniform(rng, 1.2, 1.6), w = uniform(rng, 0.6, 0.8),
                 h = uniform(rng, 0.72, 0.76);
    add_box(m, V3(0, 0, h - 0.015), V3(l, w, 0.03));
    const double ped = uniform(rng, 0.38, 0.45);
    add_box(m, V3(l / 2 - ped / 2, 0, (h - 0.03) / 2),
            V3(ped, w - 0.05, h - 0.03));  // drawer pedestal
    add_box(m, V3(-l / 2 + 0.02, 0, (h - 0.03) / 2), V3(0.03, w - 0.05, h - 0.03));  // panel leg
    add_box(m, V3(0, w / 2 - 0.05, h - 0.25), V3(l - 0.1, 0.02, 0.4));  // modesty panel
}

void folding_table(TriangleMesh& m, Rng& rng) {
    const double l = uniform(rng, 1.5, 1.9), w = uniform(rng, 0.7, 0.8),
                 h = uniform(rng, 0.72, 0.75);
    add_box(m, V3(0, 0, h - 0.02), V3(l, w, 0.04));
    for (double sx : {-1.0, 1.0}) {  // a folding leg frame at each end: two legs and a floor bar
        const double x = sx * (l / 2 - 0.2);
        for (double sy : {-1.0, 1.0})
            add_strut(m, V3(x, sy * (w / 2 - 0.08), h - 0.04),
                      V3(x + sx * 0.05, sy * (w / 2 - 0.08), 0.0), 0.025);
        add_strut(m, V3(x + sx * 0.05, -(w / 2 - 0.08), 0.0125),
                  V3(x + sx * 0.05, w / 2 - 0.08, 0.0125), 0.025);
    }
}

void side_table(TriangleMesh& m, Rng& rng) {
    const double a = uniform(rng, 0.40, 0.55), h = uniform(rng, 0.50, 0.65);
    add_box(m, V3(0, 0, h - 0.015), V3(a, a, 0.03));
    add_four_legs(m, a / 2 - 0.02, a / 2 - 0.02, h - 0.03, 0.03);
    add_box(m, V3(0, 0, 0.15), V3(a - 0.06, a - 0.06, 0.02));
}

}  // namespace

std::string_view to_string(FurnitureStyle style) { return kNames[static_cast<std::size_t>(style)]; }

std::optional<FurnitureStyle> parse_furniture_style(std::string_view name) {
    for (std::size_t i = 0; i < kNames.size(); ++i) {
        if (kNames[i] == name) return static_cast<FurnitureStyle>(i);
    }
    return std::nullopt;
}

ObjectClass class_of(FurnitureStyle style) { return kClasses[static_cast<std::size_t>(style)]; }

std::vector<FurnitureStyle> styles_of(ObjectClass cls) {
    std::vector<FurnitureStyle> out;
    for (int i = 0; i < kNumFurnitureStyles; ++i) {
        const auto s = static_cast<FurnitureStyle>(i);
        if (class_of(s) == cls) out.push_back(s);
    }
    return out;
}

std::vector<FurnitureStyle> scene_styles_of(ObjectClass cls) {
    std::vector<FurnitureStyle> out;
    for (FurnitureStyle s : styles_of(cls)) {
        if (static_cast<int>(s) <= static_cast<int>(FurnitureStyle::kConferenceTable))
            out.push_back(s);
    }
    return out;
}

FurnitureModel make_furniture(FurnitureStyle style, std::uint64_t seed) {
    Rng rng = make_rng(seed, 100 + static_cast<std::uint64_t>(style));
    FurnitureModel model;
    model.style = style;
    model.seed = seed;
    TriangleMesh& m = model.mesh_object;
    switch (style) {
        case FurnitureStyle::kFourLegChair:
            four_leg_chair(m, rng);
            break;
        case FurnitureStyle::kOfficeChair:
            office_chair(m, rng);
            break;
        case FurnitureStyle::kStool:
            stool(m, rng);
            break;
        case FurnitureStyle::kArmchair:
            armchair(m, rng);
            break;
        case FurnitureStyle::kRectTable:
            rect_table(m, rng, 1.0, 1.8, 0.6, 0.9);
            break;
        case FurnitureStyle::kRoundTable:
            round_table(m, rng);
            break;
        case FurnitureStyle::kConferenceTable:
            conference_table(m, rng);
            break;
        case FurnitureStyle::kStackingChair:
            stacking_chair(m, rng);
            break;
        case FurnitureStyle::kSledChair:
            sled_chair(m, rng);
            break;
        case FurnitureStyle::kCantileverChair:
            cantilever_chair(m, rng);
            break;
        case FurnitureStyle::kBarStool:
            bar_stool(m, rng);
            break;
        case FurnitureStyle::kFoldingChair:
            folding_chair(m, rng);
            break;
        case FurnitureStyle::kBench:
            bench(m, rng);
            break;
        case FurnitureStyle::kSofa:
            sofa(m, rng);
            break;
        case FurnitureStyle::kLoungeChair:
            lounge_chair(m, rng);
            break;
        case FurnitureStyle::kPedestalTable:
            pedestal_table(m, rng);
            break;
        case FurnitureStyle::kCoffeeTable:
            coffee_table(m, rng);
            break;
        case FurnitureStyle::kBalconyTable:
            balcony_table(m, rng);
            break;
        case FurnitureStyle::kDesk:
            desk(m, rng);
            break;
        case FurnitureStyle::kFoldingTable:
            folding_table(m, rng);
            break;
        case FurnitureStyle::kSideTable:
            side_table(m, rng);
            break;
    }
    // Centre the footprint on the origin, floor at z = 0.
    Eigen::Vector3d lo, hi;
    mesh_bounds(m, lo, hi);
    const Eigen::Vector3d shift(-(lo.x() + hi.x()) / 2, -(lo.y() + hi.y()) / 2, -lo.z());
    transform_mesh(m, make_T_xyz_yaw(shift, 0.0));
    model.box_object.size_m = hi - lo;
    model.box_object.centre_m = Eigen::Vector3d(0, 0, (hi.z() - lo.z()) / 2);
    model.box_object.yaw_rad = 0.0;
    return model;
}

}  // namespace makeway::sim

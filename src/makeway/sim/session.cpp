// Recording sessions of one building (make_session): every object's pose drawn anew from where it
// stands in the base scene, by the scene's usage profile (scene.hpp).
#include <cmath>

#include "makeway/common/angles.hpp"
#include "makeway/common/box_overlap.hpp"
#include "makeway/common/random.hpp"
#include "makeway/sim/scene_dynamics.hpp"
#include "makeway/sim/scene_generator.hpp"

namespace makeway::sim {
namespace {

// Moves a table and the chairs that belong to it by `shift` (world) and turns them by `turn` about
// the table's centre.
void move_table_group(Scene& s, const SceneObject& table, const Eigen::Vector2d& shift,
                      double turn_rad) {
    const Eigen::Vector2d centre(table.pose.x_m, table.pose.y_m);
    const Eigen::Rotation2Dd R(turn_rad);
    for (SceneObject& c : s.objects) {
        if (c.id != table.id && c.table_id != table.id) continue;
        if (turn_rad == 0.0) {  // the default profile's shift, to the bit as it always was
            c.pose.x_m += shift.x();
            c.pose.y_m += shift.y();
            continue;
        }
        const Eigen::Vector2d p =
            centre + shift + R * (Eigen::Vector2d(c.pose.x_m, c.pose.y_m) - centre);
        c.pose.x_m = p.x();
        c.pose.y_m = p.y();
        c.pose.yaw_rad = wrap_angle(c.pose.yaw_rad + turn_rad);
    }
}

// Moves a chair by (forward, left) in its own frame and turns it.
void move_chair(SceneObject& o, double forward_m, double left_m, double turn_rad) {
    const double c = std::cos(o.pose.yaw_rad), s = std::sin(o.pose.yaw_rad);
    o.pose.x_m += forward_m * c - left_m * s;
    o.pose.y_m += forward_m * s + left_m * c;
    o.pose.yaw_rad = wrap_angle(o.pose.yaw_rad + turn_rad);
}

// One session's draw of every object's pose from its base pose, by the scene's usage profile.
void draw_session(Scene& s, Rng& rng) {
    const UsageProfile usage = s.usage;
    const double table_share = usage == UsageProfile::kDefault        ? 0.15
                               : usage == UsageProfile::kTablesNudged ? 0.6
                                                                      : 0.0;
    for (const SceneObject& o : std::vector<SceneObject>(s.objects)) {
        if (o.cls != ObjectClass::kTable || !bernoulli(rng, table_share)) continue;
        if (usage == UsageProfile::kDefault) {
            // y drawn first: the sessions every benchmark so far measured drew it so.
            const double sy = normal(rng, 0, 0.25);
            const double sx = normal(rng, 0, 0.25);
            move_table_group(s, o, {sx, sy}, 0.0);
        } else {
            const double sign = bernoulli(rng, 0.5) ? 1.0 : -1.0;
            const double along = sign * uniform(rng, 0.2, 0.6);
            const double turn = normal(rng, 0, deg_to_rad(8));
            move_table_group(
                s, o, along * Eigen::Vector2d(std::cos(o.pose.yaw_rad), std::sin(o.pose.yaw_rad)),
                turn);
        }
    }
    const double chair_share = usage == UsageProfile::kDefault      ? 0.5
                               : usage == UsageProfile::kPulledBack ? 0.7
                               : usage == UsageProfile::kSideways   ? 0.6
                                                                    : 0.3;
    for (SceneObject& o : s.objects) {
        if (o.cls != ObjectClass::kChair || !bernoulli(rng, chair_share)) continue;
        // Each draw in its own statement: the order of a call's arguments is unspecified.
        if (usage == UsageProfile::kPulledBack) {
            const double back = uniform(rng, 0.35, 0.9);
            const double turn = normal(rng, 0, deg_to_rad(3));
            move_chair(o, -back, 0.0, turn);
        } else if (usage == UsageProfile::kSideways) {
            const double side = bernoulli(rng, 0.5) ? 1.0 : -1.0;
            const double back = uniform(rng, 0.1, 0.35);
            const double slide = uniform(rng, 0.25, 0.5);
            const double turn = deg_to_rad(uniform(rng, 50.0, 100.0));
            move_chair(o, -back, side * slide, side * turn);
        } else {
            // Pushed in or pulled out along its forward axis, and turned a little.
            const double d = -uniform(rng, -0.15, 0.45);
            const double turn = normal(rng, 0, deg_to_rad(12));
            move_chair(o, d, 0.0, turn);
        }
    }
}

}  // namespace

const std::vector<std::string>& usage_profile_names() {
    // In the enum's order.
    static const std::vector<std::string> names{"default", "pulled_back", "sideways",
                                                "tables_nudged"};
    return names;
}

std::optional<UsageProfile> parse_usage_profile(std::string_view name) {
    const std::vector<std::string>& names = usage_profile_names();
    for (std::size_t k = 0; k < names.size(); ++k)
        if (names[k] == name) return static_cast<UsageProfile>(k);
    return std::nullopt;
}

std::string_view to_string(UsageProfile profile) {
    return usage_profile_names().at(static_cast<std::size_t>(profile));
}

Scene make_session(const Scene& base, int session, const RobotParams& robot) {
    if (session == 0) return base;
    for (int attempt = 0; attempt < 20; ++attempt) {
        Rng rng = make_rng(base.seed, 5000 + 100 * static_cast<std::uint64_t>(session) + attempt);
        Scene s = base;
        s.name = base.name + "_session" + std::to_string(session);
        draw_session(s, rng);
        // No two objects may overlap (a chair may tuck under its own table).
        bool overlap = false;
        std::vector<OrientedBox> boxes;
        for (const SceneObject& o : s.objects)
            boxes.push_back(model_of(o).box_object.transformed(lift_to_3d(o.pose)));
        for (std::size_t i = 0; i < boxes.size() && !overlap; ++i) {
            for (std::size_t j = i + 1; j < boxes.size() && !overlap; ++j) {
                const bool related = s.objects[i].table_id == s.objects[j].id ||
                                     s.objects[j].table_id == s.objects[i].id;
                overlap = !related && iou_bev(boxes[i], boxes[j]) > 0.0;
            }
        }
        if (!overlap && is_navigable(s, robot)) return s;
    }
    return base;
}

}  // namespace makeway::sim

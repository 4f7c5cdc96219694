#include "makeway/sim/scene_generator.hpp"

#include <cmath>
#include <stdexcept>

#include "makeway/common/angles.hpp"
#include "makeway/common/box_overlap.hpp"
#include "makeway/common/random.hpp"
#include "makeway/sim/furniture.hpp"
#include "makeway/sim/route.hpp"

namespace makeway::sim {
namespace {

using V2 = Eigen::Vector2d;

struct Counts {
    double room_w_lo, room_w_hi, room_h_lo, room_h_hi;
    int tables_lo, tables_hi, free_lo, free_hi, pillars_hi, walkers;
    double pusher_share;
};

Counts counts_for(Density d) {
    switch (d) {
        case Density::kSparse:
            return {12, 15, 9, 11, 2, 3, 2, 3, 1, 0, 0.10};
        case Density::kMedium:
            return {14, 17, 10, 12, 4, 5, 4, 6, 2, 1, 0.15};
        case Density::kDense:
            return {16, 19, 11, 13, 6, 8, 7, 10, 3, 1, 0.25};
    }
    return counts_for(Density::kMedium);
}

// Builds scenes one object at a time, refusing overlaps.
class Builder {
  public:
    Builder(Scene& scene, Rng& rng) : scene_(scene), rng_(rng) {}

    OrientedBox footprint(const SceneObject& o) const {
        FurnitureModel m = make_furniture(*parse_furniture_style(o.style), o.model_seed);
        return m.box_object.transformed(lift_to_3d(o.pose));
    }

    bool free_of_keepouts(const OrientedBox& box, double margin) const {
        for (const Pose2& p : {scene_.start, scene_.waypoint, scene_.goal}) {
            OrientedBox disk{{p.x_m, p.y_m, box.centre_m.z()}, {2.2, 2.2, 10.0}, 0.0};
            if (iou_bev(box, disk) > 0.0) return false;
        }
        const V2 c = box.centre_m.head<2>();
        const double reach = 0.5 * box.size_m.head<2>().norm() + margin;
        if (c.x() - reach < wall_min_.x() || c.x() + reach > wall_max_.x() ||
            c.y() - reach < wall_min_.y() || c.y() + reach > wall_max_.y()) {
            return false;
        }
        for (const Pillar& p : scene_.pillars) {
            OrientedBox pb{{p.centre_m.x(), p.centre_m.y(), 1.0},
                           {p.size_m.x() + 2 * margin, p.size_m.y() + 2 * margin, 2.0},
                           0.0};
            if (iou_bev(box, pb) > 0.0) return false;
        }
        for (const Wall& w : scene_.walls) {
            const V2 d = w.b_m - w.a_m;
            const V2 mid = 0.5 * (w.a_m + w.b_m);
            OrientedBox wb{{mid.x(), mid.y(), 1.0},
                           {d.norm() + w.thickness_m + 2 * margin, w.thickness_m + 2 * margin, 2.0},
                           std::atan2(d.y(), d.x())};
            if (iou_bev(box, wb) > 0.0) return false;
        }
        return true;
    }

    /// Adds the object if its footprint (grown by margin) overlaps nothing but `ignore_id`.
    bool try_add(SceneObject o, double margin, std::uint32_t ignore_id = 0) {
        OrientedBox box = footprint(o);
        box.size_m += Eigen::Vector3d(2 * margin, 2 * margin, 0);
        if (!free_of_keepouts(box, 0.05)) return false;
        for (std::size_t i = 0; i < scene_.objects.size(); ++i) {
            if (scene_.objects[i].id == ignore_id) continue;
            if (iou_bev(box, boxes_[i]) > 0.0) return false;
        }
        o.id = static_cast<std::uint32_t>(scene_.objects.size() + 1);
        scene_.objects.push_back(o);
        boxes_.push_back(footprint(o));
        return true;
    }

    void set_walls(const V2& lo, const V2& hi) {
        wall_min_ = lo;
        wall_max_ = hi;
    }

    Scene& scene_;
    Rng& rng_;
    std::vector<OrientedBox> boxes_;
    V2 wall_min_, wall_max_;
};

// A wall from a to b with door gaps (centre offset along the wall, width).
void add_wall_with_doors(Scene& s, const V2& a, const V2& b,
                         std::vector<std::pair<double, double>> doors) {
    std::sort(doors.begin(), doors.end());
    const V2 dir = (b - a).normalized();
    double pos = 0.0;
    const double length = (b - a).norm();
    for (const auto& [centre, width] : doors) {
        const double gap_lo = centre - width / 2, gap_hi = centre + width / 2;
        if (gap_lo > pos) s.walls.push_back({a + pos * dir, a + gap_lo * dir});
        pos = gap_hi;
    }
    if (pos < length) s.walls.push_back({a + pos * dir, b});
}

void add_room(Scene& s, Rng& rng, double w, double h, bool partition) {
    const V2 lo(-w / 2, -h / 2), hi(w / 2, h / 2);
    s.floor_min_m = lo - V2(0.5, 0.5);
    s.floor_max_m = hi + V2(0.5, 0.5);
    add_wall_with_doors(s, {lo.x(), lo.y()}, {hi.x(), lo.y()}, {{uniform(rng, 1.5, w - 1.5), 1.0}});
    add_wall_with_doors(s, {hi.x(), lo.y()}, {hi.x(), hi.y()}, {{uniform(rng, 1.5, h - 1.5), 1.0}});
    add_wall_with_doors(s, {hi.x(), hi.y()}, {lo.x(), hi.y()}, {{uniform(rng, 1.5, w - 1.5), 1.0}});
    add_wall_with_doors(s, {lo.x(), hi.y()}, {lo.x(), lo.y()}, {});
    if (partition) {  // a half-height-of-room partition leaving a passage at one end
        const double x = uniform(rng, -w / 8, w / 8);
        const bool from_bottom = bernoulli(rng, 0.5);
        const double len = uniform(rng, 0.35, 0.5) * h;
        const V2 a(x, from_bottom ? lo.y() : hi.y());
        const V2 b(x, from_bottom ? lo.y() + len : hi.y() - len);
        s.walls.push_back({a, b});
    }
}

FurnitureStyle pick_table_style(Rng& rng, bool allow_conference) {
    const double u = uniform(rng, 0, 1);
    if (u < 0.5) return FurnitureStyle::kRectTable;
    if (u < 0.8 || !allow_conference) return FurnitureStyle::kRoundTable;
    return FurnitureStyle::kConferenceTable;
}

FurnitureStyle pick_chair_style(Rng& rng, bool at_table) {
    const double u = uniform(rng, 0, 1);
    if (at_table)
        return u < 0.5   ? FurnitureStyle::kFourLegChair
               : u < 0.9 ? FurnitureStyle::kOfficeChair
                         : FurnitureStyle::kStool;
    return u < 0.3   ? FurnitureStyle::kFourLegChair
           : u < 0.6 ? FurnitureStyle::kOfficeChair
           : u < 0.8 ? FurnitureStyle::kStool
                     : FurnitureStyle::kArmchair;
}

// Chairs around a table the way people leave them: at seats along the sitting sides, some pulled
// out, slightly off-centre and turned; some seats empty.
void seat_chairs(Builder& b, const SceneObject table, double occupancy,
                 int max_chairs = 100) {  // a copy: adding chairs reallocates the object list
    Rng& rng = b.rng_;
    const FurnitureModel tm = make_furniture(*parse_furniture_style(table.style), table.model_seed);
    const Isometry2 T_world_table = to_isometry(table.pose);
    const double L = tm.box_object.size_m.x(), W = tm.box_object.size_m.y();
    struct Seat {
        V2 edge_table;    // seat position on the table edge, table frame
        V2 normal_table;  // outward
    };
    std::vector<Seat> seats;
    if (table.style == "round_table") {
        const double r = 0.5 * L;
        const int n = std::clamp(static_cast<int>(2 * kPi * r / 0.75), 3, 6);
        const double phase = uniform(rng, 0, 2 * kPi);
        for (int k = 0; k < n; ++k) {
            const double a = phase + 2 * kPi * k / n;
            const V2 nrm(std::cos(a), std::sin(a));
            seats.push_back({r * nrm, nrm});
        }
    } else {
        const int per_side = std::max(1, static_cast<int>(L / 0.65));
        for (double side : {-1.0, 1.0}) {
            for (int k = 0; k < per_side; ++k) {
                seats.push_back({V2(-L / 2 + L * (k + 0.5) / per_side, side * W / 2), V2(0, side)});
            }
        }
    }
    const FurnitureStyle table_chairs = pick_chair_style(rng, true);
    int placed = 0;
    for (const Seat& seat : seats) {
        if (placed >= max_chairs || !bernoulli(rng, occupancy)) continue;
        SceneObject chair;
        chair.cls = ObjectClass::kChair;
        chair.style = std::string(
            to_string(bernoulli(rng, 0.8) ? table_chairs : pick_chair_style(rng, true)));
        chair.model_seed = static_cast<std::uint64_t>(uniform_int(rng, 0, 1 << 30));
        const FurnitureModel cm =
            make_furniture(*parse_furniture_style(chair.style), chair.model_seed);
        const double depth = cm.box_object.size_m.x();
        double gap = std::clamp(normal(rng, 0.05, 0.08), -0.2, 0.5);
        if (bernoulli(rng, 0.25)) gap += uniform(rng, 0.3, 0.6);  // pulled out
        const V2 tangent(-seat.normal_table.y(), seat.normal_table.x());
        const V2 centre_table = seat.edge_table + seat.normal_table * (depth / 2 + gap) +
                                tangent * normal(rng, 0.0, 0.06);
        const V2 centre = T_world_table * centre_table;
        const V2 facing = T_world_table.linear() * (-seat.normal_table);
        chair.pose = {
            centre.x(), centre.y(),
            wrap_angle(std::atan2(facing.y(), facing.x()) + normal(rng, 0, deg_to_rad(8)))};
        chair.table_id = table.id;
        if (b.try_add(chair, 0.02, table.id)) ++placed;
    }
}

// The paper's dense layouts: rows of tables with chairs on both sitting sides, the rows parallel to
// the room's long axis, chair back to chair back `passage` apart (0.8-1.5 m: wide enough for the
// robot, and narrow enough that a planner keeping 3x its radius cannot pass).
void add_table_rows(Builder& b, double x_centre, double y_first, int rows, int tables_per_row) {
    Rng& rng = b.rng_;
    double y = y_first;
    for (int r = 0; r < rows; ++r) {
        SceneObject probe;
        probe.cls = ObjectClass::kTable;
        probe.style = "rect_table";
        probe.model_seed = static_cast<std::uint64_t>(uniform_int(rng, 0, 1 << 30));
        const FurnitureModel tm = make_furniture(FurnitureStyle::kRectTable, probe.model_seed);
        const double L = tm.box_object.size_m.x(), W = tm.box_object.size_m.y();
        const double row_depth =
            W + 2 * (0.5 + 0.05);  // the table and a chair tucked in on each side
        for (int t = 0; t < tables_per_row; ++t) {
            SceneObject table = probe;
            if (t > 0)
                table.model_seed = probe.model_seed +
                                   static_cast<std::uint64_t>(t);  // a row of one model's copies
            table.pose = {x_centre + (t - 0.5 * (tables_per_row - 1)) * (L + 0.02),
                          y + 0.5 * row_depth, normal(rng, 0, deg_to_rad(1))};
            if (b.try_add(table, 0.0)) seat_chairs(b, b.scene_.objects.back(), 0.85);
        }
        y += row_depth + uniform(rng, 0.8, 1.5);
    }
}

// Rows of chairs facing one way (a lecture or waiting area), `passage` (0.8-1.5 m) between rows.
void add_chair_rows(Builder& b, double x_centre, double y_first, int rows, int per_row) {
    Rng& rng = b.rng_;
    const FurnitureStyle style =
        bernoulli(rng, 0.5) ? FurnitureStyle::kFourLegChair : FurnitureStyle::kOfficeChair;
    double y = y_first;
    for (int r = 0; r < rows; ++r) {
        for (int k = 0; k < per_row; ++k) {
            SceneObject chair;
            chair.cls = ObjectClass::kChair;
            chair.style = std::string(to_string(style));
            chair.model_seed = static_cast<std::uint64_t>(uniform_int(rng, 0, 1 << 30));
            chair.pose = {x_centre + (k - 0.5 * (per_row - 1)) * 0.62 + normal(rng, 0, 0.03),
                          y + 0.25 + normal(rng, 0, 0.03), kPi / 2 + normal(rng, 0, deg_to_rad(6))};
            b.try_add(chair, 0.0);
        }
        y += 0.5 + uniform(rng, 0.8, 1.5);
    }
}

Scene random_layout(const SceneGenParams& params, Rng& rng) {
    const Counts k = counts_for(params.density);
    Scene s;
    const double w = uniform(rng, k.room_w_lo, k.room_w_hi),
                 h = uniform(rng, k.room_h_lo, k.room_h_hi);
    add_room(s, rng, w, h, params.density != Density::kSparse && bernoulli(rng, 0.5));
    const int pillars = static_cast<int>(uniform_int(rng, 0, k.pillars_hi));
    for (int i = 0; i < pillars; ++i) {
        const double side = uniform(rng, 0.35, 0.6);
        s.pillars.push_back(
            {V2(uniform(rng, -w / 2 + 2, w / 2 - 2), uniform(rng, -h / 2 + 1.5, h / 2 - 1.5)),
             V2(side, side), 2.8});
    }
    s.start = {-w / 2 + 1.0, uniform(rng, -h / 4, h / 4), 0.0};
    s.goal = {w / 2 - 1.0, uniform(rng, -h / 4, h / 4), 0.0};
    s.waypoint = {uniform(rng, -w / 6, w / 6), uniform(rng, -h / 3, h / 3), 0.0};

    Builder b(s, rng);
    b.set_walls(V2(-w / 2, -h / 2), V2(w / 2, h / 2));
    if (params.density == Density::kDense) {
        // As in the paper's dense rooms: a block of table rows on one side of the room and rows of
        // chairs on the other, with passages of 0.8-1.5 m between rows.
        const double side =
            bernoulli(rng, 0.5) ? -1.0 : 1.0;  // the blocks stand across the way from start to goal
        add_table_rows(b, side * w / 4 + normal(rng, 0, 0.3), -h / 2 + uniform(rng, 0.4, 1.4), 4,
                       static_cast<int>(uniform_int(rng, 1, 2)));
        add_chair_rows(b, -side * w / 4 + normal(rng, 0, 0.3), -h / 2 + uniform(rng, 0.6, 1.6), 5,
                       static_cast<int>(uniform_int(rng, 4, 6)));
    }
    const int tables = static_cast<int>(uniform_int(rng, k.tables_lo, k.tables_hi));
    for (int t = 0, tries = 0; t < tables && tries < 400; ++tries) {
        SceneObject table;
        table.cls = ObjectClass::kTable;
        table.style = std::string(to_string(pick_table_style(rng, w > 14)));
        table.model_seed = static_cast<std::uint64_t>(uniform_int(rng, 0, 1 << 30));
        const double yaw = bernoulli(rng, 0.8) ? (bernoulli(rng, 0.5) ? 0.0 : kPi / 2) +
                                                     normal(rng, 0, deg_to_rad(4))
                                               : uniform(rng, -kPi, kPi);
        table.pose = {uniform(rng, -w / 2 + 1.5, w / 2 - 1.5),
                      uniform(rng, -h / 2 + 1.5, h / 2 - 1.5), wrap_angle(yaw)};
        // Room for the chairs and an aisle around the group.
        if (!b.try_add(table, 1.3)) continue;
        ++t;
        seat_chairs(b, s.objects.back(), 0.8);
    }
    const int free_chairs = static_cast<int>(uniform_int(rng, k.free_lo, k.free_hi));
    for (int c = 0, tries = 0; c < free_chairs && tries < 400; ++tries) {
        SceneObject chair;
        chair.cls = ObjectClass::kChair;
        chair.style = std::string(to_string(pick_chair_style(rng, false)));
        chair.model_seed = static_cast<std::uint64_t>(uniform_int(rng, 0, 1 << 30));
        chair.pose = {uniform(rng, -w / 2 + 0.6, w / 2 - 0.6),
                      uniform(rng, -h / 2 + 0.6, h / 2 - 0.6), uniform(rng, -kPi, kPi)};
        if (b.try_add(chair, 0.15)) ++c;
    }
    if (params.people) {
        for (const SceneObject& o : s.objects) {
            if (o.table_id != 0 && bernoulli(rng, k.pusher_share)) {
                const double period = uniform(rng, 6.0, 12.0);
                s.pushers.push_back(
                    {o.id, period, uniform(rng, 0.3, 0.5), uniform(rng, 0.0, period)});
            }
        }
    }
    return s;
}

Scene study_space(Rng& rng) {
    Scene s;
    const double w = 18.0, h = 12.0;
    add_room(s, rng, w, h, false);
    s.start = {-w / 2 + 0.9, uniform(rng, -1.0, 1.0), 0.0};
    s.goal = {w / 2 - 0.9, uniform(rng, -1.0, 1.0), 0.0};
    s.waypoint = {uniform(rng, -1.0, 1.0), 1.75, 0.0};
    Builder b(s, rng);
    b.set_walls(V2(-w / 2, -h / 2), V2(w / 2, h / 2));
    // 12 tables in 3 rows of 4; 22 chairs: two at ten tables, one at the other two.
    std::vector<int> chairs_at{2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 1, 1};
    for (std::size_t i = chairs_at.size(); i > 1; --i)
        std::swap(chairs_at[i - 1],
                  chairs_at[uniform_int(rng, 0, static_cast<std::int64_t>(i) - 1)]);
    int t = 0;
    for (double y : {-3.5, 0.0, 3.5}) {
        for (double x : {-5.4, -1.8, 1.8, 5.4}) {
            SceneObject table;
            table.cls = ObjectClass::kTable;
            table.style = "rect_table";
            table.model_seed = static_cast<std::uint64_t>(uniform_int(rng, 0, 1 << 30));
            table.pose = {x + normal(rng, 0, 0.05), y + normal(rng, 0, 0.05),
                          normal(rng, 0, deg_to_rad(2))};
            s.objects.push_back(table);
            s.objects.back().id = static_cast<std::uint32_t>(s.objects.size());
            b.boxes_.push_back(b.footprint(s.objects.back()));
            const std::size_t before = s.objects.size();
            for (int tries = 0;
                 tries < 20 && s.objects.size() - before < static_cast<std::size_t>(chairs_at[t]);
                 ++tries) {
                seat_chairs(b, s.objects[before - 1], 0.5,
                            chairs_at[t] - static_cast<int>(s.objects.size() - before));
            }
            ++t;
        }
    }
    return s;
}

}  // namespace

std::optional<Density> parse_density(std::string_view name) {
    if (name == "sparse") return Density::kSparse;
    if (name == "medium") return Density::kMedium;
    if (name == "dense") return Density::kDense;
    return std::nullopt;
}

std::optional<Layout> parse_layout(std::string_view name) {
    if (name == "random") return Layout::kRandom;
    if (name == "study_space") return Layout::kStudySpace;
    return std::nullopt;
}

std::string_view to_string(Density d) {
    return d == Density::kSparse ? "sparse" : d == Density::kMedium ? "medium" : "dense";
}

bool is_navigable(const Scene& scene, const RobotParams& robot) {
    const std::vector<ObjectModel> models = models_of(scene);
    const CollisionChecker checker(scene, models, robot);
    if (checker.collides(scene.start, 0.0)) return false;
    const NavGrid grid = make_nav_grid(scene, checker, robot);
    return mission_route(scene, grid).has_value();
}

Scene generate_scene(const SceneGenParams& params) {
    for (int attempt = 0; attempt < params.max_attempts; ++attempt) {
        Rng rng = make_rng(params.seed, 1000 + static_cast<std::uint64_t>(attempt));
        Scene s =
            params.layout == Layout::kStudySpace ? study_space(rng) : random_layout(params, rng);
        s.seed = params.seed;
        s.usage = params.usage;
        s.density = params.layout == Layout::kStudySpace ? "study_space"
                                                         : std::string(to_string(params.density));
        s.name = s.density + "_" + std::to_string(params.seed);
        if (params.layout == Layout::kStudySpace && s.objects.size() != 12 + 22)
            continue;  // seats were blocked
        if (!is_navigable(s, params.robot)) continue;
        if (params.people && params.layout == Layout::kRandom) {
            // Walkers loop between two reachable points, away from the robot's start and goal.
            const int walkers = counts_for(params.density).walkers;
            const std::vector<ObjectModel> models = models_of(s);
            RobotParams person;
            person.length_m = person.width_m = 2 * kPersonRadius_m;
            const CollisionChecker checker(s, models, person);
            const NavGrid grid =
                make_nav_grid(s, checker, person, 0.0, 0.05, kPersonRadius_m + 0.1);
            for (int k = 0, tries = 0; k < walkers && tries < 50; ++tries) {
                const Eigen::Vector2d a(uniform(rng, s.floor_min_m.x() + 2, s.floor_max_m.x() - 2),
                                        uniform(rng, s.floor_min_m.y() + 1, s.floor_max_m.y() - 1));
                const Eigen::Vector2d c(uniform(rng, s.floor_min_m.x() + 2, s.floor_max_m.x() - 2),
                                        uniform(rng, s.floor_min_m.y() + 1, s.floor_max_m.y() - 1));
                auto route = find_route(grid, a, c);
                if (!route || route_length_m(*route) < 4.0) continue;
                std::vector<Eigen::Vector2d> loop = *route;
                loop.insert(loop.end(), route->rbegin() + 1, route->rend() - 1);
                s.walkers.push_back({loop, uniform(rng, 0.8, 1.2), uniform(rng, 0, 20)});
                ++k;
            }
        }
        return s;
    }
    throw std::runtime_error("no navigable layout found in " + std::to_string(params.max_attempts) +
                             " attempts for seed " + std::to_string(params.seed));
}

}  // namespace makeway::sim

#include "makeway/eval/track_bench.hpp"

#include <chrono>
#include <cmath>
#include <set>
#include <unordered_map>

#include "makeway/common/angles.hpp"
#include "makeway/common/box_overlap.hpp"
#include "makeway/common/random.hpp"
#include "makeway/sim/route.hpp"
#include "makeway/sim/scene_dynamics.hpp"
#include "makeway/sim/scene_generator.hpp"
#include "makeway/sim/sequence.hpp"

namespace makeway::eval {
namespace {

// Yaw error modulo the class's symmetry: tables are scored modulo pi (most are rectangular),
// chairs over the full turn.
double yaw_error_deg(ObjectClass cls, double a, double b) {
    double e = std::abs(angle_diff(a, b));
    if (cls == ObjectClass::kTable) e = std::min(e, kPi - e);
    return rad_to_deg(e);
}

struct GapState {
    int last_seen_frame = -1;
    std::uint32_t track_at_last_seen = 0;
};

}  // namespace

TrackBenchResult run_track_bench(const TrackBenchParams& p,
                                 const std::function<void(int, int)>& progress) {
    TrackBenchResult result;
    std::vector<TrackingFrame> all_gt, all_tracks;
    std::size_t det_yaw_ok = 0, det_yaw_n = 0, map_yaw_ok = 0, map_yaw_n = 0, detections = 0;
    double update_s = 0.0;
    Rng rng = make_rng(p.seed, 700);
    for (int k = 0; k < p.scenes; ++k) {
        sim::SceneGenParams g;
        g.seed = p.seed + 300 + static_cast<std::uint64_t>(k);
        g.density = k % 2 ? sim::Density::kDense : sim::Density::kMedium;
        const sim::Scene scene = sim::generate_scene(g);
        const sim::RobotParams robot;
        const sim::CollisionChecker checker(scene, sim::models_of(scene), robot);
        const auto route = sim::drive_route(scene, checker, robot);
        if (!route) continue;
        sim::SequenceParams sp;
        sp.seed = p.seed + static_cast<std::uint64_t>(k);
        sim::SequenceSimulator simulator(scene, *route, sp);
        tracking::ObjectMap map(p.tracker);
        const std::vector<sim::ObjectModel> models = sim::models_of(scene);
        // The robot's map of walls: objects stand on the room's floor.
        map.set_region([&](const Eigen::Vector2d& xy) { return scene.on_floor(xy); });
        // Ids are offset per scene so that sequences concatenate into one evaluation.
        const std::uint32_t id_base = static_cast<std::uint32_t>(k) * 1000000u;
        std::unordered_map<std::uint32_t, GapState> gaps;
        std::unordered_map<std::uint32_t, int>
            false_tracks;              // born of a false positive -> birth frame
        std::set<std::uint32_t> seen;  // objects visible at least once so far
        for (int f = 0; f < p.max_frames && !simulator.reached_goal(); ++f) {
            const sim::SimFrame frame = simulator.next();
            std::unordered_map<std::uint32_t, std::size_t> points_of;
            for (std::uint32_t id : frame.points_sensor.instance) ++points_of[id];
            const Isometry3 T_sensor_world = frame.T_world_sensor.inverse();
            const Eigen::Vector3d sensor = frame.T_world_sensor.translation();
            TrackingFrame gt;
            std::set<std::uint32_t> visible_now;
            std::vector<Detection> dets;
            std::vector<bool> is_false;
            // Ground truth for the map: objects in range that have been seen at least once (the map
            // keeps objects while they are out of view); detections: objects seen in this sweep.
            auto in_range = [&](const OrientedBox& b) {
                return (b.centre_m - sensor).head<2>().norm() <= p.tracker.sensor_range_m;
            };
            for (const sim::ObjectState& o : frame.objects) {
                const bool visible =
                    points_of[o.id] >= p.min_visible_points && in_range(o.box_world);
                if (visible) seen.insert(o.id), visible_now.insert(id_base + o.id);
                if (seen.count(o.id) && in_range(o.box_world))
                    gt.push_back({id_base + o.id, o.cls, o.box_world});
                if (!visible || uniform(rng, 0, 1) < p.p_miss) continue;
                Detection d;
                d.cls = o.cls;
                d.class_probabilities = o.cls == ObjectClass::kChair
                                            ? std::array<double, 2>{0.85, 0.15}
                                            : std::array<double, 2>{0.15, 0.85};
                d.score = uniform(rng, 0.6, 1.0);
                OrientedBox b = o.box_world;
                for (int a = 0; a < 3; ++a) {
                    b.centre_m[a] +=
                        normal(rng, 0, a == 2 ? p.centre_sigma_m / 2 : p.centre_sigma_m);
                    b.size_m[a] *= std::max(0.5, 1.0 + normal(rng, 0, p.size_sigma));
                }
                const double u = uniform(rng, 0, 1);
                const int quarter = u < p.p_flip_90                      ? 1
                                    : u < 2 * p.p_flip_90                ? 3
                                    : u < 2 * p.p_flip_90 + p.p_flip_180 ? 2
                                                                         : 0;
                b.yaw_rad = wrap_angle(b.yaw_rad + quarter * kPi / 2 +
                                       normal(rng, 0, deg_to_rad(p.yaw_sigma_deg)));
                if (quarter % 2 == 1)
                    std::swap(b.size_m.x(), b.size_m.y());  // the same box, a quarter turn off
                det_yaw_ok += yaw_error_deg(o.cls, b.yaw_rad, o.box_world.yaw_rad) <= 10.0;
                ++det_yaw_n;
                d.box_sensor = b.transformed(T_sensor_world);
                dets.push_back(d);
                is_false.push_back(false);
            }
            // False positives: object-sized boxes at random places in range.
            const double expected_fp = p.false_positive_rate * static_cast<double>(gt.size());
            int fps = static_cast<int>(expected_fp) +
                      (uniform(rng, 0, 1) < expected_fp - std::floor(expected_fp) ? 1 : 0);
            for (int i = 0; i < fps; ++i) {
                Detection d;
                d.cls = bernoulli(rng, 0.5) ? ObjectClass::kChair : ObjectClass::kTable;
                d.class_probabilities = {0.5, 0.5};
                d.score = uniform(rng, 0.3, 0.8);
                const double r = uniform(rng, 1.0, p.tracker.sensor_range_m),
                             a = uniform(rng, -kPi, kPi);
                const Eigen::Vector3d size = d.cls == ObjectClass::kChair
                                                 ? Eigen::Vector3d(0.5, 0.5, 0.9)
                                                 : Eigen::Vector3d(1.4, 0.8, 0.75);
                d.box_sensor = {{r * std::cos(a), r * std::sin(a), -0.45 + size.z() / 2},
                                size,
                                uniform(rng, -kPi, kPi)};
                dets.push_back(d);
                is_false.push_back(true);
                ++result.false_positives;
            }
            detections += dets.size();

            const auto t0 = std::chrono::steady_clock::now();
            const Eigen::Vector4d floor(0, 0, 1, 0);  // the simulator's floor is z = 0
            const tracking::TrackerFrameResult r =
                map.update(dets, frame.T_world_sensor, frame.stamp_s,
                           p.use_scan_occlusion ? &frame.points_sensor : nullptr, &floor);
            update_s +=
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

            // False-positive tracks: removed, or taken over by a true detection, within 3 frames?
            for (std::size_t i = 0; i < dets.size(); ++i) {
                const auto id = static_cast<std::uint32_t>(r.track_of_detection[i]);
                const bool born = std::find(r.born.begin(), r.born.end(), id) != r.born.end();
                if (is_false[i] && born) false_tracks[id] = f;
                if (!is_false[i]) false_tracks.erase(id);
            }
            for (std::uint32_t id : r.removed) false_tracks.erase(id);
            for (auto it = false_tracks.begin(); it != false_tracks.end();) {
                if (f - it->second >= 3) {
                    ++result.false_positive_tracks_lingering;
                    it = false_tracks.erase(it);
                } else {
                    ++it;
                }
            }
            result.map_sanity.add(check_map(r.objects_world, scene, models, frame.stamp_s));
            TrackingFrame tracks;
            for (const ObjectEstimate& o : r.objects_world) {
                if (in_range(o.box_world)) tracks.push_back({id_base + o.id, o.cls, o.box_world});
                result.false_positive_tracks_output += false_tracks.count(o.id);
            }
            // Map yaw against the ground truth it overlaps best.
            for (const TrackedBox& t : tracks) {
                double best = 0.25;
                const TrackedBox* match = nullptr;
                for (const TrackedBox& gb : gt) {
                    const double iou = iou_bev(gb.box, t.box);
                    if (iou > best) best = iou, match = &gb;
                }
                if (!match) continue;
                ++map_yaw_n;
                map_yaw_ok += yaw_error_deg(match->cls, t.box.yaw_rad, match->box.yaw_rad) <= 10.0;
            }
            // Occlusion gaps: a tracked object unseen for up to 2 s, then seen again.
            for (const TrackedBox& gb : gt) {
                if (!visible_now.count(gb.id)) continue;
                GapState& s = gaps[gb.id];
                const TrackedBox* t = nullptr;
                for (const TrackedBox& tb : tracks) {
                    if (iou_3d(gb.box, tb.box) >= 0.25) t = &tb;
                }
                if (s.last_seen_frame >= 0 && f - s.last_seen_frame > 1 &&
                    f - s.last_seen_frame <= 21 && s.track_at_last_seen != 0) {
                    ++result.occlusion_gaps;
                    result.occlusion_gaps_kept += t && t->id == s.track_at_last_seen;
                }
                s.last_seen_frame = f;
                s.track_at_last_seen = t ? t->id : 0;
            }
            all_gt.push_back(std::move(gt));
            all_tracks.push_back(std::move(tracks));
        }
        if (progress) progress(k + 1, p.scenes);
    }
    result.frames = all_gt.size();
    result.overall = evaluate_tracking(all_gt, all_tracks);
    result.per_class = evaluate_tracking_per_class(all_gt, all_tracks);
    result.fps = update_s > 0 ? static_cast<double>(result.frames) / update_s : 0.0;
    result.mean_detections_per_frame =
        result.frames ? static_cast<double>(detections) / static_cast<double>(result.frames) : 0.0;
    result.yaw_within_10deg_detections =
        det_yaw_n ? static_cast<double>(det_yaw_ok) / static_cast<double>(det_yaw_n) : 0.0;
    result.yaw_within_10deg_map =
        map_yaw_n ? static_cast<double>(map_yaw_ok) / static_cast<double>(map_yaw_n) : 0.0;
    return result;
}

}  // namespace makeway::eval

#include "makeway/eval/zone_bench.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>

#include "makeway/common/angles.hpp"
#include "makeway/eval/label_bench.hpp"
#include "makeway/eval/scene_cad.hpp"
#include "makeway/sim/scene_dynamics.hpp"
#include "makeway/sim/scene_generator.hpp"
#include "makeway/sim/sequence.hpp"

namespace makeway::eval {
namespace {

std::vector<ObjectEstimate> objects_of(const sim::Scene& scene,
                                       const std::vector<sim::ObjectModel>& models) {
    return sim::object_estimates_at(scene, models, 0.0);
}

bool moved(const ObjectEstimate& a, const ObjectEstimate& b) {
    return (a.box_world.centre_m.head<2>() - b.box_world.centre_m.head<2>()).norm() > 0.05 ||
           std::abs(angle_diff(a.box_world.yaw_rad, b.box_world.yaw_rad)) > deg_to_rad(5.0);
}

// One object's zone placed at `at`, scored on its footprints `later`.
void score_object(const ObjectEstimate& at, const std::vector<ObjectEstimate>& later,
                  const costmap::AffordanceParams& hand, const costmap::AffordanceParams& learned,
                  double cell, ZoneCoverage& all, ZoneCoverage& moved_only) {
    Eigen::Vector2d lo, hi, lo2, hi2;
    costmap::zone_bounds(at, hand, lo, hi);
    costmap::zone_bounds(at, learned, lo2, hi2);
    lo = lo.cwiseMin(lo2);
    hi = hi.cwiseMax(hi2);
    for (const ObjectEstimate& o : later) {
        for (const auto& c : o.box_world.bev_corners()) {
            lo = lo.cwiseMin(c);
            hi = hi.cwiseMax(c);
        }
    }
    const int w = static_cast<int>(std::ceil((hi.x() - lo.x()) / cell)),
              h = static_cast<int>(std::ceil((hi.y() - lo.y()) / cell));
    std::vector<double> u_hand(static_cast<std::size_t>(w) * h),
        u_learned(static_cast<std::size_t>(w) * h);
    const auto centre = [&](int x, int y) -> Eigen::Vector2d {
        return lo + cell * Eigen::Vector2d(x + 0.5, y + 0.5);
    };
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            u_hand[y * w + x] = costmap::zone_coordinate(at, hand, centre(x, y));
            u_learned[y * w + x] = costmap::zone_coordinate(at, learned, centre(x, y));
        }
    }
    const std::size_t area_hand = static_cast<std::size_t>(
        std::count_if(u_hand.begin(), u_hand.end(), [](double u) { return u <= 1.0; }));
    const std::size_t area_learned = static_cast<std::size_t>(
        std::count_if(u_learned.begin(), u_learned.end(), [](double u) { return u <= 1.0; }));
    // The learned zone cut to the hand-drawn zone's area: its area_hand lowest coordinates.
    double cut = -1.0;
    if (area_hand > 0) {
        std::vector<double> sorted = u_learned;
        std::nth_element(sorted.begin(), sorted.begin() + (area_hand - 1), sorted.end());
        cut = sorted[area_hand - 1];
    }
    for (const ObjectEstimate& o : later) {
        ZoneCoverage c;
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                const Eigen::Vector2d q = centre(x, y);
                if (!o.box_world.contains({q.x(), q.y(), o.box_world.centre_m.z()})) continue;
                c.truth_cells += 1.0;
                c.in_hand_drawn += u_hand[y * w + x] <= 1.0;
                c.in_learned_equal_area += u_learned[y * w + x] <= cut;
                c.in_learned += u_learned[y * w + x] <= 1.0;
            }
        }
        c.hand_drawn_area = static_cast<double>(area_hand);
        c.learned_area = static_cast<double>(area_learned);
        c.objects = 1;
        all += c;
        if (moved(at, o)) moved_only += c;
    }
}

std::vector<zones::SessionObject> session_objects(const std::vector<ObjectEstimate>& objects,
                                                  int place, int session) {
    std::vector<zones::SessionObject> out;
    for (const ObjectEstimate& o : objects)
        out.push_back({place, session, o.cls, o.box_world, true});
    return out;
}

// The training sessions as the robot labels them: driven, auto-labelled with the scene's CAD
// models (eval/label_bench.hpp's drive), every object with a class.
std::vector<zones::SessionObject> labelled_sessions(const sim::Scene& base, int sessions,
                                                    int max_sweeps, std::uint64_t seed, int place) {
    labelling::LabelParams lp;
    lp.system.T_base_sensor = sim::SequenceParams{}.robot.T_robot_sensor();
    labelling::Labeller labeller(lp);
    drive_sessions(labeller, base, sessions, max_sweeps, seed, sim::OdometryNoiseParams{});
    const verification::CadLibrary library = scene_cad_library(base);
    const labelling::LabelResult labels = labeller.finish(&library);
    std::vector<zones::SessionObject> out;
    for (const labelling::LabelledWorldObject& o : labels.objects) {
        if (!o.cls) continue;
        out.push_back(
            {place, o.session, *o.cls, o.box_world, o.class_source == "cad" && !o.model.empty()});
    }
    return out;
}

}  // namespace

ZoneCoverage& ZoneCoverage::operator+=(const ZoneCoverage& o) {
    truth_cells += o.truth_cells;
    in_hand_drawn += o.in_hand_drawn;
    in_learned_equal_area += o.in_learned_equal_area;
    in_learned += o.in_learned;
    hand_drawn_area += o.hand_drawn_area;
    learned_area += o.learned_area;
    objects += o.objects;
    return *this;
}

costmap::LearnedZones profile_zones(const sim::Scene& scene, int sessions,
                                    const zones::ZoneLearnParams& binning) {
    std::vector<std::map<std::uint32_t, Pose2>> poses;
    std::map<std::uint32_t, ObjectClass> cls;
    for (int s = 0; s < sessions; ++s) {
        const sim::Scene session = sim::make_session(scene, s);
        std::map<std::uint32_t, Pose2> p;
        for (const sim::SceneObject& o : session.objects) {
            p[o.id] = o.pose;
            cls[o.id] = o.cls;
        }
        poses.push_back(std::move(p));
    }
    std::vector<Pose2> motions[2];
    for (std::size_t a = 0; a < poses.size(); ++a) {
        for (std::size_t b = 0; b < poses.size(); ++b) {
            if (a == b) continue;
            for (const auto& [id, pa] : poses[a]) {
                const auto it = poses[b].find(id);
                if (it == poses[b].end()) continue;
                motions[cls[id] == ObjectClass::kChair ? 0 : 1].push_back(between(pa, it->second));
            }
        }
    }
    costmap::LearnedZones z = binning.zone;
    z.prior_strength = 0.0;
    if (!motions[0].empty()) z.chair = zones::bin_motions(motions[0], ObjectClass::kChair, binning);
    if (!motions[1].empty()) z.table = zones::bin_motions(motions[1], ObjectClass::kTable, binning);
    return z;
}

costmap::LearnedZones building_zones(const sim::Scene& scene, int sessions,
                                     const zones::ZoneLearnParams& learn) {
    if (sessions < 2)
        throw std::invalid_argument("zones of a building: at least 2 sessions to learn from, got " +
                                    std::to_string(sessions));
    const std::vector<sim::ObjectModel> models = sim::models_of(scene);
    std::vector<zones::SessionObject> train;
    for (int s = kProfileSessions; s < kProfileSessions + sessions; ++s) {
        const auto more = session_objects(objects_of(sim::make_session(scene, s), models), 0, s);
        train.insert(train.end(), more.begin(), more.end());
    }
    return zones::learn_zones(train, learn).zones;
}

ZoneBenchResult run_zone_bench(const ZoneBenchParams& p,
                               const std::function<void(std::size_t, std::size_t)>& progress) {
    ZoneBenchResult out;
    out.scenes.resize(static_cast<std::size_t>(p.scenes));
    std::vector<std::vector<zones::SessionObject>> training(out.scenes.size());
    std::vector<std::vector<zones::ObjectMotion>> training_tracks(out.scenes.size());
    std::mutex mutex;
    std::size_t done = 0;
    const auto one_scene = [&](int i) {
        sim::SceneGenParams g;
        g.seed = p.seed + static_cast<std::uint64_t>(i);
        g.density = i % 2 == 0 ? sim::Density::kMedium : sim::Density::kDense;
        g.usage = p.usage;
        const sim::Scene base = sim::generate_scene(g);
        const std::vector<sim::ObjectModel> models = sim::models_of(base);
        std::vector<std::vector<ObjectEstimate>> sessions;
        for (int s = 0; s < p.train_sessions + p.test_sessions; ++s)
            sessions.push_back(objects_of(sim::make_session(base, s, g.robot), models));
        ZoneBenchScene& r = out.scenes[static_cast<std::size_t>(i)];
        r.name = base.name;
        std::vector<zones::SessionObject>& train = training[static_cast<std::size_t>(i)];
        if (p.source == ZoneSource::kLabels) {
            const auto t_label = std::chrono::steady_clock::now();
            train = labelled_sessions(base, p.train_sessions, p.max_sweeps,
                                      p.seed * 7919 + static_cast<std::uint64_t>(i) * 31, i);
            r.label_seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t_label).count();
        } else {
            for (int s = 0; s < p.train_sessions; ++s) {
                const auto more = session_objects(sessions[s], i, s);
                train.insert(train.end(), more.begin(), more.end());
            }
        }
        std::vector<zones::ObjectMotion> tracked;
        if (p.track_gap_s > 0.0 && p.source == ZoneSource::kTruth) {
            std::vector<zones::TrackedObject> seen;
            for (int s = 0; s < p.train_sessions; ++s) {
                const sim::Scene session = sim::make_session(base, s, g.robot);
                for (double t = 0.0; t <= p.track_duration_s; t += 1.0) {
                    for (const ObjectEstimate& o : sim::object_estimates_at(session, models, t))
                        seen.push_back({i * 1000 + s, o.id, t, o.cls, o.box_world});
                }
            }
            tracked = zones::track_motions(seen, p.track_gap_s);
        }
        const auto t0 = std::chrono::steady_clock::now();
        const zones::ZoneLearning l = zones::learn_zones(train, p.learn, tracked);
        training_tracks[static_cast<std::size_t>(i)] = tracked;
        r.learn_seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        r.chair_learning = l.chair;
        r.table_learning = l.table;
        costmap::AffordanceParams learned = p.hand_drawn;
        learned.learned = std::make_shared<const costmap::LearnedZones>(l.zones);
        const std::vector<ObjectEstimate>& last = sessions[p.train_sessions - 1];
        for (std::size_t k = 0; k < last.size(); ++k) {
            std::vector<ObjectEstimate> later;
            for (int s = p.train_sessions; s < p.train_sessions + p.test_sessions; ++s) {
                for (const ObjectEstimate& o : sessions[s])
                    if (o.id == last[k].id) later.push_back(o);
            }
            const bool chair = last[k].cls == ObjectClass::kChair;
            score_object(last[k], later, p.hand_drawn, learned, p.cell_m, chair ? r.chair : r.table,
                         chair ? r.chair_moved : r.table_moved);
        }
        std::lock_guard<std::mutex> lock(mutex);
        if (progress) progress(++done, out.scenes.size());
    };
    // The labeller spreads its own work over the cores: its scenes go one after the other.
    if (p.source == ZoneSource::kLabels) {
        for (int i = 0; i < p.scenes; ++i) one_scene(i);
    } else {
        tbb::parallel_for(0, p.scenes, one_scene);
    }
    std::vector<zones::SessionObject> all;
    for (const auto& t : training) all.insert(all.end(), t.begin(), t.end());
    std::vector<zones::ObjectMotion> all_tracks;
    for (const auto& t : training_tracks) all_tracks.insert(all_tracks.end(), t.begin(), t.end());
    out.pooled = zones::learn_zones(all, p.learn, all_tracks).zones;
    out.total.name = "total";
    for (const ZoneBenchScene& s : out.scenes) {
        out.total.chair += s.chair;
        out.total.table += s.table;
        out.total.chair_moved += s.chair_moved;
        out.total.table_moved += s.table_moved;
        out.total.learn_seconds += s.learn_seconds;
        out.total.label_seconds += s.label_seconds;
        for (const auto& [from, to] : {std::pair{&s.chair_learning, &out.total.chair_learning},
                                       std::pair{&s.table_learning, &out.total.table_learning}}) {
            const double n = static_cast<double>(to->motions + from->motions);
            if (n > 0)
                to->mean_confidence = (to->mean_confidence * static_cast<double>(to->motions) +
                                       from->mean_confidence * static_cast<double>(from->motions)) /
                                      n;
            to->moved_share = n > 0 ? (to->moved_share * static_cast<double>(to->motions) +
                                       from->moved_share * static_cast<double>(from->motions)) /
                                          n
                                    : 0.0;
            to->observations += from->observations;
            to->motions += from->motions;
            to->unmatched += from->unmatched;
            to->unsure += from->unsure;
            to->facing_unknown += from->facing_unknown;
        }
    }
    return out;
}

}  // namespace makeway::eval

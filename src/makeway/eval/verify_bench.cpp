#include "makeway/eval/verify_bench.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "makeway/common/angles.hpp"
#include "makeway/common/random.hpp"
#include "makeway/common/statistics.hpp"
#include "makeway/common/stopwatch.hpp"
#include "makeway/perception/accumulator.hpp"
#include "makeway/perception/ground.hpp"
#include "makeway/pipeline/keyframe.hpp"
#include "makeway/sim/furniture.hpp"
#include "makeway/sim/lidar.hpp"
#include "makeway/sim/scene_generator.hpp"

namespace makeway::eval {
namespace {

struct Sample {
    double yaw_before_deg, yaw_after_deg, centre_before_m, centre_after_m;
    bool accepted, scored_yaw;
};

OrientationStats stats(const std::vector<Sample>& samples, bool after) {
    OrientationStats s;
    std::vector<double> yaw, centre;
    std::size_t w10 = 0, w30 = 0;
    for (const Sample& x : samples) {
        if (after && !x.accepted) continue;
        centre.push_back(after ? x.centre_after_m : x.centre_before_m);
        if (!x.scored_yaw) continue;
        const double e = after ? x.yaw_after_deg : x.yaw_before_deg;
        yaw.push_back(e);
        w10 += e <= 10.0;
        w30 += e <= 30.0;
    }
    s.objects = centre.size();
    s.yaw_within_10deg = yaw.empty() ? 0.0 : static_cast<double>(w10) / yaw.size();
    s.yaw_within_30deg = yaw.empty() ? 0.0 : static_cast<double>(w30) / yaw.size();
    s.median_yaw_error_deg = median(yaw);
    s.median_centre_error_m = median(centre);
    return s;
}

// Which library an object is verified against: its own model plus one of every other style of its
// class (matched); other dimensions of its style instead of its own (mismatched); its own model
// scaled by 0.9-1.1 per axis, as a CAD library of similar furniture has it (scaled).
enum class Arm { kMatched, kMismatched, kScaled };
constexpr int kArms = 3;

verification::CadLibrary build_library(const sim::SceneObject& o, Arm arm) {
    verification::CadLibrary lib;
    for (sim::FurnitureStyle style : sim::scene_styles_of(o.cls)) {
        const bool own = std::string(sim::to_string(style)) == o.style;
        const std::uint64_t seed = own && arm != Arm::kMismatched
                                       ? o.model_seed
                                       : o.model_seed + 7919 + static_cast<std::uint64_t>(style);
        TriangleMesh mesh = sim::make_furniture(style, seed).mesh_object;
        if (own && arm == Arm::kScaled) {
            Rng rng = make_rng(o.model_seed, 77);
            const Eigen::Vector3f scale(static_cast<float>(uniform(rng, 0.9, 1.1)),
                                        static_cast<float>(uniform(rng, 0.9, 1.1)),
                                        static_cast<float>(uniform(rng, 0.9, 1.1)));
            for (Eigen::Vector3f& v : mesh.vertices_m) v = v.cwiseProduct(scale);
        }
        lib.add(std::string(sim::to_string(style)) + "_" + std::to_string(seed), o.cls, mesh);
    }
    return lib;
}

// Libraries are sampled once per (object model, arm). Scene objects get a cache per scene (their
// model seeds are the scene's own); the false boxes' two proxies share one for the whole run.
class LibraryCache {
  public:
    const verification::CadLibrary& get(const sim::SceneObject& o, Arm arm) {
        const std::string key = o.style + "/" + std::to_string(o.model_seed) + "/" +
                                std::to_string(static_cast<int>(arm));
        auto it = cache_.find(key);
        if (it == cache_.end()) it = cache_.emplace(key, build_library(o, arm)).first;
        return it->second;
    }

  private:
    std::map<std::string, verification::CadLibrary> cache_;
};

}  // namespace

std::optional<double> yaw_error_deg(const std::string& style, double a, double b) {
    if (style == "round_table" || style == "stool") return std::nullopt;
    double e = std::abs(angle_diff(a, b));
    if (style == "rect_table" || style == "conference_table") e = std::min(e, kPi - e);
    return rad_to_deg(e);
}

double BenchKeyframe::floor_z_m(const Eigen::Vector3d& c) const {
    return ground.floor_z_at(c.x(), c.y());
}

BenchKeyframe simulate_bench_keyframe(std::uint64_t seed, int k) {
    BenchKeyframe kf;
    sim::SceneGenParams g;
    g.seed = seed + 100 + static_cast<std::uint64_t>(k);
    g.density = k % 2 ? sim::Density::kDense : sim::Density::kMedium;
    g.people = false;
    kf.scene = sim::generate_scene(g);
    kf.models = sim::models_of(kf.scene);
    sim::World world(kf.scene, kf.models);
    kf.T_world_sensor = lift_to_3d(kf.scene.waypoint, 0.45);
    perception::KeyframeAccumulator acc;
    for (int s = 0; s < 5; ++s) {
        perception::StampedSweep sw;
        sw.stamp_s = 0.1 * s;
        sw.points_sensor = sim::simulate_sweep(
            world, {}, [&](double) { return kf.T_world_sensor; }, sw.stamp_s, seed + k, s);
        sw.T_world_sensor_start = sw.T_world_sensor_end = kf.T_world_sensor;
        acc.add(std::move(sw));
    }
    const PointCloud raw = acc.keyframe();
    pipeline::KeyframeParams keyframe;
    keyframe.ground.seed = seed;
    pipeline::PreparedKeyframe prepared = pipeline::prepare_keyframe(raw, keyframe);
    kf.ground = prepared.ground;
    kf.cloud_sensor = std::move(prepared.cloud_sensor);
    return kf;
}

VerifyBenchResult run_verify_bench(const VerifyBenchParams& p,
                                   const std::function<void(int, int)>& progress) {
    VerifyBenchResult result;
    std::vector<Sample> samples[kArms];
    std::vector<double> ms[kArms];
    std::size_t true_rejected[kArms] = {}, false_accepted[kArms] = {}, approximate[kArms] = {};
    Rng rng = make_rng(p.seed, 500);
    LibraryCache proxy_libraries;
    for (int k = 0; k < p.scenes; ++k) {
        LibraryCache libraries;
        const BenchKeyframe kf = simulate_bench_keyframe(p.seed, k);
        const sim::Scene& scene = kf.scene;
        const std::vector<sim::ObjectModel>& models = kf.models;
        const Isometry3& T_world_sensor = kf.T_world_sensor;
        const PointCloud& cloud = kf.cloud_sensor;
        auto floor_z = [&](const Eigen::Vector3d& c) { return kf.floor_z_m(c); };
        std::map<std::uint32_t, std::size_t> points_of;
        for (std::uint32_t id : cloud.instance) ++points_of[id];

        for (std::size_t i = 0; i < scene.objects.size(); ++i) {
            const sim::SceneObject& o = scene.objects[i];
            if (points_of[o.id] < p.min_points) continue;
            const Isometry3 T_sensor_object = T_world_sensor.inverse() * lift_to_3d(o.pose);
            const OrientedBox truth = models[i].box_object.transformed(T_sensor_object);
            // Corrupt the box the way detectors fail.
            Detection det;
            det.cls = o.cls;
            det.box_sensor = truth;
            for (int a = 0; a < 3; ++a) {
                det.box_sensor.centre_m[a] +=
                    normal(rng, 0, a == 2 ? p.centre_sigma_m / 2 : p.centre_sigma_m);
                det.box_sensor.size_m[a] *= std::max(0.5, 1.0 + normal(rng, 0, p.size_sigma));
            }
            const double u = uniform(rng, 0, 1);
            const double flip = u < p.p_flip_90                      ? kPi / 2
                                : u < 2 * p.p_flip_90                ? -kPi / 2
                                : u < 2 * p.p_flip_90 + p.p_flip_180 ? kPi
                                                                     : 0.0;
            det.box_sensor.yaw_rad =
                wrap_angle(truth.yaw_rad + flip + normal(rng, 0, deg_to_rad(p.yaw_sigma_deg)));
            ++result.true_boxes;
            for (int arm = 0; arm < kArms; ++arm) {
                const verification::CadLibrary& lib = libraries.get(o, static_cast<Arm>(arm));
                const auto t0 = SteadyClock::now();
                const verification::VerifiedDetection v = verification::verify_detection(
                    cloud, det, lib, p.verify, floor_z(det.box_sensor.centre_m));
                ms[arm].push_back(ms_since(t0));
                Sample smp;
                smp.accepted = v.accepted;
                true_rejected[arm] += !v.accepted;
                approximate[arm] += v.approximate;
                const auto yb =
                    yaw_error_deg(o.style, det.box_sensor.yaw_rad, yaw_of(T_sensor_object));
                const auto ya =
                    yaw_error_deg(o.style, yaw_of(v.T_sensor_object), yaw_of(T_sensor_object));
                smp.scored_yaw = yb.has_value();
                smp.yaw_before_deg = yb.value_or(0.0);
                smp.yaw_after_deg = ya.value_or(0.0);
                smp.centre_before_m = (det.box_sensor.centre_m - truth.centre_m).head<2>().norm();
                smp.centre_after_m = (v.box_sensor.centre_m - truth.centre_m).head<2>().norm();
                samples[arm].push_back(smp);
            }
        }
        // False boxes: chair-sized boxes on structure points (walls, pillars) away from furniture.
        std::vector<std::size_t> structure;
        for (std::size_t i = 0; i < cloud.size(); ++i) {
            if (cloud.label[i] == static_cast<std::uint8_t>(SemanticLabel::kStructure))
                structure.push_back(i);
        }
        for (int f = 0; f < p.false_boxes_per_scene && !structure.empty(); ++f) {
            const Eigen::Vector3d c =
                cloud
                    .xyz[structure[static_cast<std::size_t>(
                        uniform_int(rng, 0, static_cast<std::int64_t>(structure.size()) - 1))]]
                    .cast<double>();
            Detection det;
            det.cls = bernoulli(rng, 0.5) ? ObjectClass::kChair : ObjectClass::kTable;
            det.box_sensor = {
                {c.x(), c.y(), floor_z(c) + 0.45}, {0.55, 0.5, 0.9}, uniform(rng, -kPi, kPi)};
            if (det.cls == ObjectClass::kTable) det.box_sensor.size_m = {1.4, 0.8, 0.75};
            ++result.false_boxes;
            sim::SceneObject proxy;
            proxy.cls = det.cls;
            proxy.style = det.cls == ObjectClass::kChair ? "four_leg_chair" : "rect_table";
            for (int arm = 0; arm < kArms; ++arm) {
                const verification::CadLibrary& lib =
                    proxy_libraries.get(proxy, static_cast<Arm>(arm));
                false_accepted[arm] +=
                    verification::verify_detection(cloud, det, lib, p.verify, floor_z(c)).accepted;
            }
        }
        if (progress) progress(k + 1, p.scenes);
    }
    for (int arm = 0; arm < kArms; ++arm) {
        VerifyBenchArm& a = arm == 0   ? result.matched
                            : arm == 1 ? result.mismatched
                                       : result.scaled;
        a.before = stats(samples[arm], false);
        a.after = stats(samples[arm], true);
        a.true_rejection_rate =
            result.true_boxes ? static_cast<double>(true_rejected[arm]) / result.true_boxes : 0.0;
        a.approximate_rate =
            result.true_boxes ? static_cast<double>(approximate[arm]) / result.true_boxes : 0.0;
        a.false_acceptance_rate =
            result.false_boxes ? static_cast<double>(false_accepted[arm]) / result.false_boxes
                               : 0.0;
        a.ms_per_object_median = median(ms[arm]);
        a.ms_per_object_p99 = percentile(ms[arm], 0.99);
    }
    return result;
}

}  // namespace makeway::eval

#include "makeway/eval/detection_eval.hpp"

#include <algorithm>
#include <map>
#include <optional>

#include "makeway/common/statistics.hpp"
#include "makeway/common/stopwatch.hpp"
#include "makeway/eval/scene_cad.hpp"
#include "makeway/pipeline/pipeline.hpp"
#include "makeway/verification/verifier.hpp"

namespace makeway::eval {
namespace {

// Median and p99 of the detector's latency on the first keyframes, with `threads` threads.
std::pair<double, double> latency_ms(const perception::Detector& detector,
                                     const std::vector<LabelledKeyframe>& kfs, int count,
                                     int threads) {
    perception::set_inference_threads(threads);
    std::vector<double> ms;
    for (int i = 0; i < std::min<int>(count, static_cast<int>(kfs.size())); ++i) {
        const auto t0 = SteadyClock::now();
        const LabelledKeyframe& kf = kfs[static_cast<std::size_t>(i)];
        (void)detector.detect(kf.cloud_sensor, kf.ground_plane_sensor);
        ms.push_back(ms_since(t0));
    }
    return {percentile(ms, 0.5), percentile(ms, 0.99)};
}

}  // namespace

DetectionEvalResult run_detection_eval(
    const perception::Detector& detector, const DetectionEvalParams& p,
    const std::function<void(const std::string&, int, int)>& progress) {
    DetectionEvalResult r;
    std::optional<verification::CadLibrary> default_library;  // built only when asked for
    if (p.cad == CadSource::kDefault) default_library = default_cad_library();
    enum Arm { kHeldOut, kLeftOut, kReal, kClutter };
    std::vector<Arm> arms{kHeldOut, kLeftOut};
    if (!p.real_held_out.empty()) arms.push_back(kReal);
    if (p.clutter.count > 0) arms.push_back(kClutter);
    for (const Arm arm : arms) {
        DatasetParams dp;
        dp.scenes = p.scenes;
        dp.seed = p.seed + static_cast<std::uint64_t>(arm) * 1000;
        dp.keyframe_every = p.keyframe_every;
        dp.max_keyframes_per_scene = p.max_keyframes_per_scene;
        dp.system = p.system;
        dp.beam_pattern = p.beam_pattern;
        dp.sensor_height_m = p.sensor_height_m;
        if (arm == kLeftOut)
            dp.only_styles = p.left_out_styles;
        else
            dp.exclude_styles = p.left_out_styles;
        if (arm == kReal) {
            dp.furniture = p.real_held_out;
            dp.furniture_share = 1.0;
        }
        if (arm == kClutter) {
            dp.clutter = p.clutter;
            dp.clutter_only = true;
        }
        static constexpr const char* kWhat[] = {"held-out scenes", "left-out styles",
                                                "real models held out", "clutter"};
        const std::string what = kWhat[arm];
        std::vector<sim::Scene> scenes;
        const std::vector<LabelledKeyframe> kfs = generate_detection_dataset(
            dp,
            [&](int d, int t) {
                if (progress) progress(what, d, t);
            },
            &scenes);
        // Network, then verification against the CAD library of the keyframe's scene; the
        // verified stage ranks by the network's score, the map fuses p_exist.
        std::map<std::uint32_t, verification::CadLibrary> scene_libraries;
        std::vector<std::vector<Detection>> net, ver, evidence;
        for (const LabelledKeyframe& kf : kfs) {
            net.push_back(detector.detect(kf.cloud_sensor, kf.ground_plane_sensor));
            static const verification::CadLibrary kNoModels;
            const verification::CadLibrary* lib = default_library             ? &*default_library
                                                  : p.cad == CadSource::kNone ? &kNoModels
                                                                              : nullptr;
            if (!lib) {
                auto it = scene_libraries.find(kf.sequence);
                if (it == scene_libraries.end())
                    it = scene_libraries
                             .emplace(kf.sequence,
                                      scene_cad_library(scenes.at(kf.sequence), p.cad_fit))
                             .first;
                lib = &it->second;
            }
            // The floor under a detection from the front end's fitted plane, as the pipeline does.
            perception::GroundPlaneResult ground;
            if (kf.ground_plane_sensor) {
                ground.found = true;
                ground.normal = kf.ground_plane_sensor->head<3>();
                ground.offset = (*kf.ground_plane_sensor)(3);
            }
            const auto floor_z = [&](double x, double y) -> std::optional<double> {
                if (!ground.found) return std::nullopt;
                return ground.floor_z_at(x, y);
            };
            if (lib->models().empty() && !p.shape_prior) {
                // Nothing to verify against: the pipeline maps the network's boxes, chairs turned
                // to their backs, its scores as the evidence (Pipeline::perceive); so does this.
                ver.push_back(verification::chairs_turned_to_their_backs(
                    kf.cloud_sensor, net.back(), floor_z, p.system.back_yaw));
                evidence.push_back(ver.back());
                continue;
            }
            const auto verified = verification::verify_detections(
                kf.cloud_sensor, net.back(), *lib, p.system.verify, floor_z, p.shape_prior);
            ver.push_back(verification::accepted_detections(
                verified, verification::ScoreFrom::kDetector, p.system.verify.keep_unfitted));
            evidence.push_back(verification::accepted_detections(
                verified, verification::ScoreFrom::kExistence, p.system.verify.keep_unfitted));
        }
        const tracking::TrackerParams tracker =
            pipeline::tracker_params_for(&detector, p.system.tracker, p.cad != CadSource::kNone);
        if (arm == kClutter) {
            ClutterMetrics c;
            c.keyframes = kfs.size();
            for (const sim::Scene& scene : scenes) c.clutter_items += scene.environment.size();
            for (const auto& d : net) {
                c.network += d.size();
                for (const Detection& x : d) c.network_scores.push_back(x.score);
            }
            for (const auto& d : track_keyframes(kfs, evidence, tracker, dp.range_m))
                c.tracked += d.size();
            r.clutter = c;
            continue;
        }
        StageMetrics& s = arm == kHeldOut   ? r.held_out
                          : arm == kLeftOut ? r.left_out
                                            : r.real_held_out.emplace();
        std::vector<std::vector<LabelledBox>> gt;
        for (const LabelledKeyframe& kf : kfs) gt.push_back(ground_truth_of(kf));
        s.network = evaluate_detections(net, gt);
        s.verified = evaluate_detections(ver, gt);
        s.tracked = evaluate_detections(track_keyframes(kfs, evidence, tracker, dp.range_m),
                                        map_ground_truth_of(kfs));
        s.keyframes = kfs.size();
        if (arm == kHeldOut) {
            std::tie(r.latency_ms_median_1t, r.latency_ms_p99_1t) =
                latency_ms(detector, kfs, p.latency_keyframes, 1);
            std::tie(r.latency_ms_median_2t, r.latency_ms_p99_2t) =
                latency_ms(detector, kfs, p.latency_keyframes, 2);
        }
    }
    return r;
}

}  // namespace makeway::eval

#include "makeway/eval/detection_eval.hpp"

#include <algorithm>
#include <chrono>

#include "makeway/common/statistics.hpp"
#include "makeway/eval/perception_source.hpp"
#include "makeway/verification/verifier.hpp"

namespace makeway::eval {
namespace {

std::vector<Detection> verify_all(const LabelledKeyframe& kf, const std::vector<Detection>& dets, const verification::CadLibrary& lib) {
    std::vector<Detection> out;
    const double floor_z = -0.45;  // keyframes are in the sensor frame of a level LiDAR 0.45 m up
    for (const Detection& d : dets) {
        const verification::VerifiedDetection v = verification::verify_detection(kf.cloud_sensor, d, lib, {}, floor_z);
        if (!v.accepted) continue;
        Detection r = d;
        r.box_sensor = v.box_sensor;
        out.push_back(r);
    }
    return out;
}

}  // namespace

std::vector<LabelledBox> ground_truth_of(const LabelledKeyframe& kf) {
    std::vector<LabelledBox> out;
    for (const LabelledObject& o : kf.objects) {
        const bool round = o.style == "round_table" || o.style == "stool";
        out.push_back({o.cls, o.box_sensor, !round, o.cls == ObjectClass::kTable});
    }
    return out;
}

DetectionEvalResult run_detection_eval(const perception::Detector& detector, const DetectionEvalParams& p,
                                       const std::function<void(const std::string&, int, int)>& progress) {
    DetectionEvalResult r;
    const verification::CadLibrary lib = default_cad_library();
    for (int arm = 0; arm < 2; ++arm) {
        DatasetParams dp;
        dp.scenes = p.scenes;
        dp.seed = p.seed + static_cast<std::uint64_t>(arm) * 1000;
        if (arm == 0) dp.exclude_styles = p.left_out_styles;
        else dp.only_styles = p.left_out_styles;
        const std::vector<LabelledKeyframe> kfs = generate_detection_dataset(dp, [&](int d, int t) {
            if (progress) progress(arm == 0 ? "held-out scenes" : "left-out styles", d, t);
        });
        std::vector<std::vector<Detection>> net, ver;
        std::vector<std::vector<LabelledBox>> gt;
        for (const LabelledKeyframe& kf : kfs) {
            net.push_back(detector.detect(kf.cloud_sensor));
            ver.push_back(p.verification ? verify_all(kf, net.back(), lib) : net.back());
            gt.push_back(ground_truth_of(kf));
        }
        (arm == 0 ? r.network : r.left_out_network) = evaluate_detections(net, gt);
        (arm == 0 ? r.verified : r.left_out_verified) = evaluate_detections(ver, gt);
        (arm == 0 ? r.keyframes : r.left_out_keyframes) = kfs.size();
        if (arm == 0) {
            for (int threads : {1, 2}) {
                perception::set_inference_threads(threads);
                std::vector<double> ms;
                for (int i = 0; i < std::min<int>(p.latency_keyframes, static_cast<int>(kfs.size())); ++i) {
                    const auto t0 = std::chrono::steady_clock::now();
                    (void)detector.detect(kfs[static_cast<std::size_t>(i)].cloud_sensor);
                    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
                }
                (threads == 1 ? r.latency_ms_median_1t : r.latency_ms_median_2t) = percentile(ms, 0.5);
                (threads == 1 ? r.latency_ms_p99_1t : r.latency_ms_p99_2t) = percentile(ms, 0.99);
            }
        }
    }
    return r;
}

}  // namespace makeway::eval

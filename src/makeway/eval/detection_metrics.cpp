#include "makeway/eval/detection_metrics.hpp"

#include <algorithm>
#include <cmath>

#include "makeway/common/angles.hpp"
#include "makeway/common/box_overlap.hpp"

namespace makeway::eval {

double average_precision(const std::vector<bool>& hit, std::size_t positives) {
    if (positives == 0 || hit.empty()) return 0.0;
    std::vector<double> precision, recall;
    std::size_t tp = 0;
    for (std::size_t i = 0; i < hit.size(); ++i) {
        tp += hit[i];
        precision.push_back(static_cast<double>(tp) / static_cast<double>(i + 1));
        recall.push_back(static_cast<double>(tp) / static_cast<double>(positives));
    }
    // Precision envelope (monotone from the right), integrated over the recall steps.
    for (std::size_t i = precision.size() - 1; i > 0; --i)
        precision[i - 1] = std::max(precision[i - 1], precision[i]);
    double ap = 0.0, last_recall = 0.0;
    for (std::size_t i = 0; i < hit.size(); ++i) {
        ap += (recall[i] - last_recall) * precision[i];
        last_recall = recall[i];
    }
    return ap;
}

DetectionMetrics evaluate_detections(const std::vector<std::vector<Detection>>& detections,
                                     const std::vector<std::vector<LabelledBox>>& ground_truth) {
    DetectionMetrics out;
    int classes_with_gt = 0;
    for (ObjectClass cls : kAllObjectClasses) {
        ClassDetectionMetrics m;
        struct Ranked {
            double score;
            std::size_t frame, index;
        };
        std::vector<Ranked> ranked;
        for (std::size_t k = 0; k < detections.size(); ++k) {
            for (std::size_t i = 0; i < detections[k].size(); ++i) {
                if (detections[k][i].cls == cls) ranked.push_back({detections[k][i].score, k, i});
            }
        }
        std::stable_sort(ranked.begin(), ranked.end(),
                         [](const Ranked& a, const Ranked& b) { return a.score > b.score; });
        for (const auto& f : ground_truth)
            m.ground_truth += static_cast<std::size_t>(std::count_if(
                f.begin(), f.end(), [&](const LabelledBox& g) { return g.cls == cls; }));
        m.detections = ranked.size();
        std::size_t yaw_n = 0, yaw10 = 0, yaw30 = 0;
        for (const double thr : {0.25, 0.5}) {
            std::vector<std::vector<bool>> taken(ground_truth.size());
            for (std::size_t k = 0; k < ground_truth.size(); ++k)
                taken[k].assign(ground_truth[k].size(), false);
            std::vector<bool> hit;
            for (const Ranked& r : ranked) {
                const Detection& d = detections[r.frame][r.index];
                double best = thr;
                int match = -1;
                const auto& gts = r.frame < ground_truth.size() ? ground_truth[r.frame]
                                                                : std::vector<LabelledBox>{};
                for (std::size_t g = 0; g < gts.size(); ++g) {
                    if (gts[g].cls != cls || taken[r.frame][g]) continue;
                    const double iou = iou_3d(d.box_sensor, gts[g].box);
                    if (iou >= best) best = iou, match = static_cast<int>(g);
                }
                hit.push_back(match >= 0);
                if (match < 0) continue;
                taken[r.frame][static_cast<std::size_t>(match)] = true;
                const LabelledBox& g = gts[static_cast<std::size_t>(match)];
                if (thr == 0.25 && g.yaw_scored) {
                    double e = std::abs(angle_diff(d.box_sensor.yaw_rad, g.box.yaw_rad));
                    if (g.pi_symmetric) e = std::min(e, kPi - e);
                    ++yaw_n;
                    yaw10 += rad_to_deg(e) <= 10.0;
                    yaw30 += rad_to_deg(e) <= 30.0;
                }
            }
            const double ap = average_precision(hit, m.ground_truth);
            const double ar = m.ground_truth
                                  ? static_cast<double>(std::count(hit.begin(), hit.end(), true)) /
                                        static_cast<double>(m.ground_truth)
                                  : 0.0;
            (thr == 0.25 ? m.ap_25 : m.ap_50) = ap;
            (thr == 0.25 ? m.ar_25 : m.ar_50) = ar;
        }
        m.yaw_within_10deg = yaw_n ? static_cast<double>(yaw10) / static_cast<double>(yaw_n) : 0.0;
        m.yaw_within_30deg = yaw_n ? static_cast<double>(yaw30) / static_cast<double>(yaw_n) : 0.0;
        if (m.ground_truth) {
            ++classes_with_gt;
            out.map_25 += m.ap_25, out.map_50 += m.ap_50, out.mar_25 += m.ar_25,
                out.mar_50 += m.ar_50;
        }
        out.per_class[cls] = m;
    }
    if (classes_with_gt) {
        out.map_25 /= classes_with_gt, out.map_50 /= classes_with_gt, out.mar_25 /= classes_with_gt,
            out.mar_50 /= classes_with_gt;
    }
    return out;
}

}  // namespace makeway::eval

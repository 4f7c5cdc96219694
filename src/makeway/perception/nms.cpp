#include "makeway/perception/nms.hpp"

#include <algorithm>

#include "makeway/common/box_overlap.hpp"

namespace makeway::perception {

std::vector<Detection> rotated_nms(std::vector<Detection> dets, const NmsParams& params) {
    std::stable_sort(dets.begin(), dets.end(),
                     [](const Detection& a, const Detection& b) { return a.score > b.score; });
    std::vector<Detection> kept;
    for (const Detection& d : dets) {
        if (kept.size() >= params.max_detections) break;
        const bool suppressed = std::any_of(kept.begin(), kept.end(), [&](const Detection& k) {
            if (params.per_class && k.cls != d.cls) return false;
            // Cheap reject before the exact polygon overlap.
            const double reach =
                0.5 * (k.box_sensor.size_m.head<2>().norm() + d.box_sensor.size_m.head<2>().norm());
            if ((k.box_sensor.centre_m - d.box_sensor.centre_m).head<2>().norm() >= reach)
                return false;
            return iou_bev(k.box_sensor, d.box_sensor) > params.max_bev_iou;
        });
        if (!suppressed) kept.push_back(d);
    }
    return kept;
}

}  // namespace makeway::perception

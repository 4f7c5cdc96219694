#include "makeway/eval/keyframe_stages.hpp"

#include <cmath>
#include <set>

namespace makeway::eval {
namespace {

LabelledBox box_of(const LabelledObject& o) {
    const bool round = o.style == "round_table" || o.style == "stool";
    return {o.cls, o.box_sensor, !round, o.cls == ObjectClass::kTable};
}

}  // namespace

std::vector<LabelledBox> ground_truth_of(const LabelledKeyframe& kf) {
    std::vector<LabelledBox> out;
    for (const LabelledObject& o : kf.objects) out.push_back(box_of(o));
    return out;
}

std::vector<std::vector<LabelledBox>> map_ground_truth_of(
    const std::vector<LabelledKeyframe>& kfs) {
    std::vector<std::vector<LabelledBox>> out;
    std::set<std::uint32_t> seen;
    for (std::size_t i = 0; i < kfs.size(); ++i) {
        if (i > 0 && kfs[i].sequence != kfs[i - 1].sequence) seen.clear();
        std::vector<LabelledBox> gt = ground_truth_of(kfs[i]);
        for (const LabelledObject& o : kfs[i].unseen) {
            if (seen.count(o.id)) gt.push_back(box_of(o));
        }
        for (const LabelledObject& o : kfs[i].objects) seen.insert(o.id);
        out.push_back(std::move(gt));
    }
    return out;
}

std::vector<std::vector<Detection>> track_keyframes(
    const std::vector<LabelledKeyframe>& kfs, const std::vector<std::vector<Detection>>& detections,
    const tracking::TrackerParams& params, double range_m) {
    std::vector<std::vector<Detection>> out;
    tracking::ObjectMap map(params);
    for (std::size_t i = 0; i < kfs.size(); ++i) {
        if (i > 0 && kfs[i].sequence != kfs[i - 1].sequence) map = tracking::ObjectMap(params);
        const Isometry3 T_sensor_world = kfs[i].T_world_sensor.inverse();
        std::vector<Detection> objects;
        for (const ObjectEstimate& o :
             map.update(detections[i], kfs[i].T_world_sensor, kfs[i].stamp_s).objects_world) {
            Detection d;
            d.box_sensor = o.box_world.transformed(T_sensor_world);
            if (std::abs(d.box_sensor.centre_m.x()) > range_m ||
                std::abs(d.box_sensor.centre_m.y()) > range_m)
                continue;
            d.cls = o.cls;
            d.class_probabilities.fill(0.0);
            d.class_probabilities[static_cast<std::size_t>(o.cls)] = 1.0;
            d.score = o.existence;
            objects.push_back(d);
        }
        out.push_back(std::move(objects));
    }
    return out;
}

}  // namespace makeway::eval

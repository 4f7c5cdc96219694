// makeway track's KITTI path (track_kitti.hpp).
#include "apps/track_kitti.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <map>
#include <set>
#include <unordered_map>

#include "io/file_util.hpp"
#include "makeway/common/angles.hpp"

namespace makeway::apps {

namespace {

using Clock = std::chrono::steady_clock;
using io::to_lower;

}  // namespace

// The frames after its last detection that a confirmed track's predicted box is written for, per
// KITTI type: -1 none, 0 until the track is dropped. By default each type's preset, chosen on the
// 10 training sequences in shared/kitti_tracking: pedestrians one frame (sAMOTA 0.698 -> 0.726,
// MOTA 0.642 -> 0.669, by the devkit's rules 0.566 -> 0.605; two frames 0.726 / 0.648 / 0.591,
// until dropped 0.717 / 0.646 / 0.577), cars and cyclists none (one frame: Car MOTA 0.823 ->
// 0.779, Cyclist sAMOTA 0.627 -> 0.593). With --config the file's tracker replaces the preset,
// and so does none here.
int coasting_frames_for(const TrackOptions& o, const std::string& type) {
    if (o.no_coasting) return -1;
    if (o.coasting) return o.coasting_frames;
    return o.config.empty() && to_lower(type) == "pedestrian" ? 1 : -1;
}

std::vector<io::KittiTrackingRecord> track_kitti_sequence(
    const KittiSequenceInput& in, const std::vector<std::string>& types,
    const std::map<std::string, tracking::TrackerParams>& params_of, const TrackOptions& o,
    TrackRun& run) {
    int last = -1;
    for (const auto& r : in.records) last = std::max(last, r.frame);
    std::set<int>
        updated;  // frames at which a map was updated (empty stretches with no objects are skipped)
    std::map<std::pair<std::string, std::uint32_t>, int>
        out_id;  // (type, map id) -> id in the output
    std::vector<io::KittiTrackingRecord> out;
    const double half_fov = deg_to_rad(o.fov_deg) / 2;
    for (const std::string& type : types) {
        std::map<int, std::vector<std::size_t>> frames;  // frame -> record indices of this type
        for (std::size_t i = 0; i < in.records.size(); ++i) {
            if (to_lower(in.records[i].type) == to_lower(type))
                frames[in.records[i].frame].push_back(i);
        }
        if (frames.empty()) continue;
        const tracking::TrackerParams& params = params_of.at(type);
        const int coasting_frames = coasting_frames_for(o, type);
        tracking::ObjectMap map(params);
        std::unordered_map<std::uint32_t, std::size_t> last_record;  // map id -> its last detection
        std::unordered_map<std::uint32_t, std::vector<io::KittiTrackingRecord>>
            pending;  // unconfirmed tracks' boxes
        std::unordered_map<std::uint32_t, std::pair<double, int>>
            score_sums;  // detections' scores per track
        for (int f = 0; f <= last; ++f) {
            const auto it = frames.find(f);
            if (it == frames.end() &&
                map.tracks().empty()) {  // nothing to predict or judge: skip to the next detections
                const auto next = frames.upper_bound(f);
                if (next == frames.end()) break;
                f = next->first - 1;
                continue;
            }
            std::vector<Detection> dets;
            const std::vector<std::size_t> idx =
                it == frames.end() ? std::vector<std::size_t>{} : it->second;
            for (std::size_t i : idx) {
                Detection d;
                d.cls = ObjectClass::kChair;  // one class per map: its index 0
                d.class_probabilities = {1.0, 0.0};
                d.box_sensor = io::box_from_kitti(in.records[i]);
                d.score = in.records[i].score.value_or(1.0);
                dets.push_back(d);
            }
            const Clock::time_point t0 = Clock::now();
            const tracking::TrackerFrameResult r =
                map.update(dets, Isometry3::Identity(), f / o.rate_hz);
            run.update_s += std::chrono::duration<double>(Clock::now() - t0).count();
            updated.insert(f);
            // Output: boxes updated by a detection this frame (and the predicted boxes of confirmed
            // tracks without one, as coasting_frames_for allows); a track's boxes from before it
            // was confirmed wait in `pending` and go out when it is (--no-backfill: they are
            // dropped).
            std::unordered_map<std::uint32_t, std::size_t>
                detection_of;  // map id -> record index matched now
            for (std::size_t k = 0; k < idx.size(); ++k) {
                if (r.track_of_detection[k] < 0) continue;
                const auto id = static_cast<std::uint32_t>(r.track_of_detection[k]);
                detection_of[id] = last_record[id] = idx[k];
            }
            std::vector<std::uint32_t> ids;
            for (const auto& [id, t] : map.tracks()) ids.push_back(id);
            std::sort(ids.begin(), ids.end());
            for (std::uint32_t id : ids) {
                const tracking::Track& t = map.tracks().at(id);
                const auto det = detection_of.find(id);
                const bool detected = det != detection_of.end();
                const bool confirmed = t.confirmed(params.min_hits);
                const bool coasts = confirmed && coasting_frames >= 0 &&
                                    (coasting_frames == 0 || t.misses <= coasting_frames);
                if (!detected && !coasts) continue;
                const Eigen::Vector3d& c = t.filter.box().centre_m;
                if (o.fov_deg > 0.0 &&
                    (c.x() <= 0.0 || std::abs(std::atan2(c.y(), c.x())) > half_fov))
                    continue;
                const std::size_t rec_index = detected ? det->second : last_record.at(id);
                const io::KittiTrackingRecord& d = in.records[rec_index];
                double score = t.existence();
                if (o.output_score != "existence") {
                    auto& [sum, n] = score_sums[id];
                    if (detected) sum += d.score.value_or(1.0), ++n;
                    score = o.output_score == "detection" ? d.score.value_or(1.0)
                                                          : sum / std::max(n, 1);
                }
                io::KittiTrackingRecord rec = io::to_kitti(t.filter.box(), type, f, -1, score);
                rec.bbox_px = d.bbox_px, rec.truncated = d.truncated, rec.occluded = d.occluded;
                if (!confirmed) {
                    if (o.backfill) pending[id].push_back(rec);
                    continue;
                }
                const auto [id_it, fresh] =
                    out_id.try_emplace({type, id}, static_cast<int>(out_id.size()));
                if (fresh) ++run.tracks_per_class[type];
                if (const auto p = pending.find(id); p != pending.end()) {
                    for (io::KittiTrackingRecord& early : p->second) {
                        early.track_id = id_it->second;
                        out.push_back(early);
                    }
                    pending.erase(p);
                }
                rec.track_id = id_it->second;
                out.push_back(rec);
            }
            for (auto pit = pending.begin();
                 pit != pending.end();) {  // tracks removed before confirmation
                pit = map.tracks().count(pit->first) ? std::next(pit) : pending.erase(pit);
            }
        }
    }
    run.frames += updated.size();
    std::stable_sort(out.begin(), out.end(),
                     [](const auto& a, const auto& b) { return a.frame < b.frame; });
    return out;
}

std::vector<std::string> kitti_types(const std::vector<KittiSequenceInput>& inputs,
                                     const TrackOptions& o) {
    std::vector<std::string> present;
    for (const auto& in : inputs) {
        for (const auto& r : in.records) {
            if (!r.is_dont_care() &&
                std::find(present.begin(), present.end(), r.type) == present.end())
                present.push_back(r.type);
        }
    }
    if (o.classes.empty()) return present;
    std::vector<std::string> out;
    for (const std::string& c : o.classes) {
        const auto it = std::find_if(present.begin(), present.end(), [&](const std::string& t) {
            return to_lower(t) == to_lower(c);
        });
        if (it == present.end()) std::cout << "class " << c << ": no detections in the input\n";
        out.push_back(it == present.end() ? c : *it);
    }
    return out;
}

}  // namespace makeway::apps

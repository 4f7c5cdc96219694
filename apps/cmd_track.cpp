// makeway track: the tracker on detections, makeway frames or KITTI files.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <unordered_map>

#include "apps/command.hpp"
#include "io/config_reader.hpp"
#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/pose_io.hpp"
#include "io/progress.hpp"
#include "io/staged_output.hpp"
#include "io/tracking_io.hpp"
#include "makeway/common/angles.hpp"
#include "makeway/tracking/object_map.hpp"

namespace makeway::apps {

struct TrackOptions {
    std::string detections;  ///< folder of per-frame JSON (makeway) or KITTI file / folder of files
    std::string format = "makeway";
    std::string poses;   ///< TUM sensor poses per frame (makeway format, optional)
    std::string config;  ///< YAML; its tracking section (default: built-in, KITTI preset for kitti)
    double rate_hz = 10.0;  ///< frame rate for KITTI files (stamps = frame / rate)
    std::optional<double> range_m, min_score;
    std::vector<std::string>
        classes;  ///< empty: every class in the input (kitti), chair and table (makeway)
    std::string score_transform = "auto";  ///< auto, none or sigmoid
    std::string out_of_range;              ///< freeze or drop; empty: the configuration's
    double fov_deg = 0.0;  ///< > 0: KITTI output only within this horizontal field of view
    std::string output_score = "detection";  ///< kitti: detection, existence or track-mean
    bool coasting = false;    ///< kitti: boxes of confirmed tracks not detected in the frame, every
                              ///< type (default: the type's preset)
    int coasting_frames = 0;  ///< kitti, with coasting: at most this many frames after the last
                              ///< detection (0: until dropped)
    bool no_coasting = false;  ///< kitti: no such boxes for any type
    bool backfill = true;      ///< kitti: a confirmed track's output starts at its first detection
    std::string out;
};

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

using io::to_lower;

std::string_view name_of(tracking::ScoreTransform t) {
    return t == tracking::ScoreTransform::kSigmoid ? "sigmoid" : "none";
}

// The tracker's settings: the configuration (or the format's preset for `type`), then the command
// line.
tracking::TrackerParams tracker_params(const TrackOptions& o, const std::string& type = "car") {
    tracking::TrackerParams p =
        o.format == "kitti" ? tracking::traffic_preset(type) : tracking::TrackerParams{};
    if (!o.config.empty()) p = io::load_config(o.config).system.tracker;
    // KITTI types are chosen by --classes; each type's map tracks its own boxes (as index 0, whose
    // motion prior applies), whatever chair/table selection the configuration makes.
    if (o.format == "kitti") p.tracked_classes.fill(true);
    if (o.range_m) p.sensor_range_m = *o.range_m;
    if (o.min_score) p.min_score = *o.min_score;
    if (!o.out_of_range.empty())
        p.out_of_range =
            o.out_of_range == "drop" ? tracking::OutOfRange::kDrop : tracking::OutOfRange::kFreeze;
    if (o.format == "makeway" && !o.classes.empty()) {
        p.tracked_classes.fill(false);
        for (const std::string& c : o.classes) {
            const auto cls = parse_object_class(to_lower(c));
            if (!cls)
                throw io::FileError("--classes", "unknown class '" + c +
                                                     "' (makeway detections are chair or table)");
            p.tracked_classes[static_cast<std::size_t>(*cls)] = true;
        }
    }
    if (const auto problems = p.validate(); !problems.empty())
        throw io::FileError(o.config.empty() ? "track options" : o.config, problems.front());
    return p;
}

// sigmoid: as asked. none: a score outside [0, 1] is an error (never clamped). auto: the
// configuration's transform, or the sigmoid when any score lies outside [0, 1] (raw logits).
tracking::ScoreTransform resolve_score_transform(
    const TrackOptions& o, tracking::ScoreTransform configured,
    const std::vector<std::pair<std::string, double>>& scores) {
    if (o.score_transform == "sigmoid") return tracking::ScoreTransform::kSigmoid;
    const auto outside = std::find_if(scores.begin(), scores.end(), [](const auto& s) {
        return !(s.second >= 0.0 && s.second <= 1.0);
    });
    if (o.score_transform == "none") {
        if (outside != scores.end()) {
            std::ostringstream what;
            what << "score " << outside->second
                 << " is not in [0, 1]; raw logits need --score-transform sigmoid";
            throw io::FileError(outside->first, what.str());
        }
        return tracking::ScoreTransform::kNone;
    }
    if (configured == tracking::ScoreTransform::kSigmoid || outside == scores.end())
        return configured;
    std::cout << "scores outside [0, 1] (" << outside->first << ": " << outside->second
              << "): read as logits through the sigmoid (--score-transform none refuses them)\n";
    return tracking::ScoreTransform::kSigmoid;
}

struct KittiSequenceInput {
    fs::path file;
    std::vector<io::KittiTrackingRecord> records;
};

struct TrackRun {
    std::size_t frames = 0;  // frames the tracker processed
    double update_s = 0.0;   // tracker updates only: reading and writing excluded
    std::map<std::string, std::size_t> tracks_per_class;
};

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

// One sequence, one object map per class (as AB3DMOT): every frame, also those without
// detections; each output box carries its last detection's 2D box, truncation and occlusion.
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

// The classes to track: the requested ones, or every type in the input but DontCare.
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

io::Json settings_json(const tracking::TrackerParams& p) {
    return {{"sensor_range_m", p.sensor_range_m},
            {"min_score", p.min_score},
            {"score_transform", name_of(p.score_transform)},
            {"out_of_range", p.out_of_range == tracking::OutOfRange::kDrop ? "drop" : "freeze"},
            {"min_hits", p.min_hits},
            {"max_misses", p.max_misses},
            {"min_giou", p.min_giou},
            {"max_centre_distance_m", p.max_centre_distance_m},
            {"min_existence", p.min_existence},
            {"merge_iou", p.merge_iou},
            {"accel_sigma_mps2", p.kalman.accel_sigma_mps2},
            {"position_sigma_mps", p.kalman.position_sigma_mps},
            {"initial_velocity_sigma_mps", p.kalman.initial_velocity_sigma_mps},
            {"meas_position_sigma_m", p.kalman.meas_position_sigma_m}};
}

// `per_type` (kitti): each type's settings; else `p` for all.
void write_summary(const fs::path& file, const TrackOptions& o, const tracking::TrackerParams& p,
                   const TrackRun& run, std::size_t sequences,
                   const std::map<std::string, tracking::TrackerParams>* per_type = nullptr) {
    const double fps = run.update_s > 0.0 ? static_cast<double>(run.frames) / run.update_s : 0.0;
    io::Json j{{"format", o.format},         {"sequences", sequences},
               {"frames", run.frames},       {"tracker_seconds", run.update_s},
               {"frames_per_second", fps},   {"tracks_per_class", run.tracks_per_class},
               {"tracker", settings_json(p)}};
    if (per_type) {
        io::Json t = io::Json::object();
        io::Json coasting = io::Json::object();
        for (const auto& [type, params] : *per_type) {
            t[type] = settings_json(params);
            coasting[type] = coasting_frames_for(o, type);
        }
        j["tracker"] = t;
        j["coasting_frames_per_type"] = coasting;  // -1: none, 0: until dropped
    }
    if (o.format == "kitti") {
        j["rate_hz"] = o.rate_hz, j["fov_deg"] = o.fov_deg;
        j["output_score"] = o.output_score, j["coasting"] = o.coasting,
        j["coasting_frames"] = o.coasting_frames;
        j["backfill"] = o.backfill;
    }
    io::write_json(file, j);
    std::cout << std::fixed << std::setprecision(1) << "tracked " << run.frames << " frames in "
              << std::setprecision(3) << run.update_s
              << " s of tracker updates: " << std::setprecision(0) << fps
              << " frames per second (one core)\n";
}

int run_track_kitti(const TrackOptions& o) {
    const tracking::TrackerParams checked =
        tracker_params(o);  // the configuration and options checked before any file is read
    std::vector<KittiSequenceInput> inputs;
    std::vector<std::pair<std::string, double>> scores;
    for (const auto& f : io::kitti_sequence_files(o.detections)) {
        inputs.push_back({f, io::read_kitti_tracking(f)});
        for (const auto& r : inputs.back().records) {
            if (r.score && !r.is_dont_care()) scores.emplace_back(f.string(), *r.score);
        }
    }
    const std::vector<std::string> types = kitti_types(inputs, o);
    const tracking::ScoreTransform transform =
        resolve_score_transform(o, checked.score_transform, scores);
    std::map<std::string, tracking::TrackerParams>
        params_of;  // the preset per type (or the configuration)
    for (const std::string& type : types) {
        // A configuration replaces the presets for every type alike: read once, in `checked`.
        tracking::TrackerParams p = o.config.empty() ? tracker_params(o, type) : checked;
        p.score_transform = transform;
        params_of.emplace(type, p);
    }
    // Every input is read and tracked before anything is written: bad input leaves no output.
    TrackRun run;
    std::vector<std::vector<io::KittiTrackingRecord>> tracks;
    io::ProgressBar bar("track", inputs.size());
    for (const auto& in : inputs) {
        tracks.push_back(track_kitti_sequence(in, types, params_of, o, run));
        bar.update(tracks.size());
    }
    bar.finish();
    io::StagedOutput staged(o.out);
    for (std::size_t k = 0; k < inputs.size(); ++k) {
        io::write_kitti_tracking(staged.staging() / inputs[k].file.filename(),
                                 tracks[k]);  // empty: an empty file
    }
    write_summary(staged.staging() / "summary.json", o, checked, run, inputs.size(), &params_of);
    staged.commit();
    std::cout << "classes:";
    for (const auto& t : types)
        std::cout << " " << t << " (" << run.tracks_per_class[t] << " tracks)";
    std::cout << "\nwrote " << inputs.size() << " sequence(s) to " << o.out << "\n";
    return 0;
}

}  // namespace

int run_track(const TrackOptions& o) {
    if (o.format == "kitti") return run_track_kitti(o);
    tracking::TrackerParams params = tracker_params(o);
    std::vector<fs::path> files;
    for (const auto& f : io::frame_files(o.detections, "json")) {
        if (f.filename() != "summary.json") files.push_back(f);
    }
    std::vector<io::DetectionFrame> frames;
    std::vector<std::pair<std::string, double>> scores;
    for (const auto& f : files) {
        frames.push_back(io::read_detection_frame(f, /*any_score=*/true));
        for (const Detection& d : frames.back().detections_sensor)
            scores.emplace_back(f.string(), d.score);
    }
    params.score_transform = resolve_score_transform(o, params.score_transform, scores);
    if (!o.poses.empty()) {
        const auto poses = io::read_tum(o.poses);
        if (poses.size() < frames.size()) {
            throw io::FileError(o.poses, "holds " + std::to_string(poses.size()) + " poses for " +
                                             std::to_string(frames.size()) + " frames");
        }
        for (std::size_t k = 0; k < frames.size(); ++k)
            frames[k].T_world_sensor = poses[k].T_world_sensor;
    }
    // Stamps checked before the progress bar starts: one error, one line. Frames without stamps are
    // taken at 10 Hz.
    std::vector<double> stamps;
    for (std::size_t k = 0; k < frames.size(); ++k) {
        stamps.push_back(frames[k].stamp_s != 0.0 || k == 0 ? frames[k].stamp_s
                                                            : static_cast<double>(k) / 10.0);
        if (k > 0 && stamps[k] < stamps[k - 1])
            throw io::FileError(files[k].string(), "stamp_s goes back in time");
    }
    tracking::ObjectMap map(params);
    std::vector<io::Json> results;
    TrackRun run;
    io::ProgressBar bar("track", frames.size());
    for (std::size_t k = 0; k < frames.size(); ++k) {
        const double stamp = stamps[k];
        const Clock::time_point t0 = Clock::now();
        const auto r = map.update(frames[k].detections_sensor,
                                  frames[k].T_world_sensor.value_or(Isometry3::Identity()), stamp);
        run.update_s += std::chrono::duration<double>(Clock::now() - t0).count();
        for (std::uint32_t id : r.born)
            ++run.tracks_per_class[std::string(to_string(map.tracks().at(id).cls()))];
        results.push_back(io::objects_to_json(static_cast<int>(k), stamp, r.objects_world));
        bar.update(k + 1);
    }
    bar.finish();
    run.frames = frames.size();
    io::StagedOutput staged(o.out);
    for (std::size_t k = 0; k < frames.size(); ++k)
        io::write_json(staged.staging() / files[k].filename(), results[k]);
    write_summary(staged.staging() / "summary.json", o, params, run, 1);
    staged.commit();
    std::cout << "tracked " << frames.size() << " frames: " << map.objects().size()
              << " objects in the map; wrote " << o.out << "\n";
    return 0;
}

// The subcommands of this file, as --help lists them.
namespace {

void declare_track(CommandSpec& c, TrackOptions& o) {
    c.option("--detections", o.detections,
             "makeway: folder of per-frame JSON ({\"stamp_s\", \"T_world_sensor\", "
             "\"detections\"}); kitti: a tracking-format file or a folder of them")
        .required();
    c.option("--format", o.format, "makeway or kitti").choices({"makeway", "kitti"}).show_default();
    c.option("--poses", o.poses, "TUM file of T_world_sensor, one per frame (makeway format)");
    c.option("--config", o.config,
             "YAML configuration: its tracking section (default: built-in; for kitti a "
             "traffic preset per type: 80 m range, drop out of range, constant velocity, "
             "README \"Tracking on KITTI\")");
    c.option("--rate", o.rate_hz, "Frame rate of KITTI sequences [Hz]")
        .range(0.1, 1000.0)
        .show_default();
    c.option("--range", o.range_m,
             "Sensor range [m]: farther objects are neither matched nor judged")
        .range(0.1, 10000.0);
    c.option("--classes", o.classes,
             "Classes to track, comma separated (kitti: any type names, default every "
             "type in the input but DontCare; makeway: chair, table)")
        .delimiter(',');
    c.option("--min-score", o.min_score,
             "Detections scoring below this (after --score-transform) are not used");
    c.option("--score-transform", o.score_transform,
             "How scores become probabilities: none, sigmoid (raw "
             "logits), or auto (sigmoid when any score is outside [0, 1])")
        .choices({"auto", "none", "sigmoid"})
        .show_default();
    c.option("--out-of-range", o.out_of_range,
             "Objects leaving the range: freeze (kept where last seen) or drop")
        .choices({"freeze", "drop"});
    c.option("--fov-deg", o.fov_deg,
             "kitti: write only objects within this horizontal field of view of the "
             "sensor's x axis (KITTI's camera: 81.4)")
        .range(0.0, 360.0);
    c.option("--output-score", o.output_score,
             "kitti: the score written per box: detection (the matched "
             "detection's, as given), existence (the track's fused "
             "existence) or track-mean (the mean of its detections' so far)")
        .choices({"detection", "existence", "track-mean"})
        .show_default();
    auto& coast = c.flag("--coasting", o.coasting,
                         "kitti: also write confirmed tracks of every type in frames "
                         "without a detection (their predicted boxes); default: each "
                         "type's preset (Pedestrian one frame, the others none)");
    c.flag("--no-coasting", o.no_coasting,
           "kitti: only boxes updated by a detection, for every type")
        .excludes(coast);
    c.option("--coasting-frames", o.coasting_frames,
             "kitti, with --coasting: write a track's predicted box "
             "at most this many frames after its last detection (0: "
             "until the track is dropped)")
        .range(0, 1000)
        .needs(coast);
    c.flag("!--no-backfill", o.backfill,
           "kitti: a track's output starts at the frame that confirms it (default: "
           "at its first detection, the frames that led to it written too, as AB3DMOT)");
    c.option("--out", o.out,
             "Output folder: per-frame JSON objects, or one KITTI file per sequence; and "
             "summary.json (frames per second, settings)")
        .required();
}
const Registration<TrackOptions> kTrack{
    "track", Group::kRecordedData,
    "Track objects across frames (GIoU + Hungarian, Kalman filters, class and "
    "existence fusion, occlusion) and write the object map per frame",
    declare_track, run_track};

}  // namespace

}  // namespace makeway::apps

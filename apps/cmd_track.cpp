// makeway track: the tracker on detections, makeway frames or KITTI files.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

#include "apps/command.hpp"
#include "apps/track_kitti.hpp"
#include "io/config_reader.hpp"
#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/pose_io.hpp"
#include "io/progress.hpp"
#include "io/staged_output.hpp"
#include "io/tracking_io.hpp"
#include "makeway/tracking/object_map.hpp"

namespace makeway::apps {

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

// makeway track, eval-tracking and bench track.
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>

#include "apps/commands.hpp"
#include "io/error.hpp"
#include "io/pose_io.hpp"
#include "io/progress.hpp"
#include "io/tracking_io.hpp"
#include "makeway/eval/track_bench.hpp"
#include "makeway/tracking/object_map.hpp"

namespace makeway::apps {
namespace {

namespace fs = std::filesystem;

// KITTI inputs: one file, or every .txt of a folder (one sequence each).
std::vector<fs::path> kitti_sequences(const std::string& path) {
    if (fs::is_regular_file(path)) return {path};
    return io::frame_files(path, "txt");
}

std::vector<io::KittiTrackingRecord> track_kitti_sequence(const fs::path& file, double rate_hz) {
    std::map<int, std::vector<Detection>> frames;
    int last = -1;
    for (const auto& r : io::read_kitti_tracking(file)) {
        last = std::max(last, r.frame);
        const auto cls = io::class_of_kitti_type(r.type);
        if (!cls) continue;  // only chairs and tables are tracked
        Detection d;
        d.cls = *cls;
        d.box_sensor = io::box_from_kitti(r);
        d.score = std::clamp(r.score.value_or(1.0), 0.0, 1.0);
        d.class_probabilities.fill(0.0);
        d.class_probabilities[static_cast<std::size_t>(*cls)] = 1.0;
        frames[r.frame].push_back(d);
    }
    tracking::ObjectMap map;
    std::vector<io::KittiTrackingRecord> out;
    for (int f = 0; f <= last; ++f) {  // every frame, also those without detections
        const auto it = frames.find(f);
        const auto r = map.update(it == frames.end() ? std::vector<Detection>{} : it->second, Isometry3::Identity(), f / rate_hz);
        for (const ObjectEstimate& o : r.objects_world) out.push_back(io::to_kitti(o.box_world, o.cls, f, static_cast<int>(o.id), o.existence));
    }
    return out;
}

}  // namespace

int run_track(const TrackOptions& o) {
    // Every input is read and tracked before anything is written: bad input leaves no output.
    if (o.format == "kitti") {
        const auto files = kitti_sequences(o.detections);
        std::vector<std::vector<io::KittiTrackingRecord>> tracks;
        for (const auto& f : files) tracks.push_back(track_kitti_sequence(f, o.rate_hz));
        fs::create_directories(o.out);
        for (std::size_t k = 0; k < files.size(); ++k) {
            io::write_kitti_tracking(fs::path(o.out) / files[k].filename(), tracks[k]);
            std::cout << files[k].filename().string() << ": " << tracks[k].size() << " track boxes\n";
        }
        std::cout << "wrote " << files.size() << " sequence(s) to " << o.out << "\n";
        return 0;
    }
    const auto files = io::frame_files(o.detections, "json");
    std::vector<io::DetectionFrame> frames;
    for (const auto& f : files) frames.push_back(io::read_detection_frame(f));
    if (!o.poses.empty()) {
        const auto poses = io::read_tum(o.poses);
        if (poses.size() < frames.size()) {
            throw io::FileError(o.poses, "holds " + std::to_string(poses.size()) + " poses for " + std::to_string(frames.size()) + " frames");
        }
        for (std::size_t k = 0; k < frames.size(); ++k) frames[k].T_world_sensor = poses[k].T_world_sensor;
    }
    tracking::ObjectMap map;
    std::vector<io::Json> results;
    io::ProgressBar bar("track", frames.size());
    double last_stamp = -1e300;
    for (std::size_t k = 0; k < frames.size(); ++k) {
        // Frames without stamps are taken at 10 Hz.
        const double stamp = frames[k].stamp_s != 0.0 || k == 0 ? frames[k].stamp_s : static_cast<double>(k) / 10.0;
        if (stamp < last_stamp) throw io::FileError(files[k].string(), "stamp_s goes back in time");
        last_stamp = stamp;
        const auto r = map.update(frames[k].detections_sensor, frames[k].T_world_sensor.value_or(Isometry3::Identity()), stamp);
        results.push_back(io::objects_to_json(static_cast<int>(k), stamp, r.objects_world));
        bar.update(k + 1);
    }
    bar.finish();
    const fs::path out(o.out);
    fs::create_directories(out);
    for (std::size_t k = 0; k < frames.size(); ++k) io::write_json(out / files[k].filename(), results[k]);
    std::cout << "tracked " << frames.size() << " frames: " << map.objects().size() << " objects in the map; wrote " << o.out << "\n";
    return 0;
}

namespace {

std::vector<eval::TrackingFrame> kitti_frames(const fs::path& file, bool use_track_ids) {
    std::vector<eval::TrackingFrame> frames;
    for (const auto& r : io::read_kitti_tracking(file)) {
        const auto cls = io::class_of_kitti_type(r.type);
        if (!cls) continue;
        if (r.track_id < 0 && use_track_ids) throw io::FileError(file.string(), "frame " + std::to_string(r.frame) + ": a line without a track id");
        if (frames.size() <= static_cast<std::size_t>(r.frame)) frames.resize(static_cast<std::size_t>(r.frame) + 1);
        frames[static_cast<std::size_t>(r.frame)].push_back({static_cast<std::uint32_t>(r.track_id), *cls, io::box_from_kitti(r)});
    }
    return frames;
}

io::Json metrics_json(const eval::TrackingMetrics& m) {
    return {{"mota", m.clear.mota}, {"motp", m.clear.motp}, {"id_switches", m.clear.id_switches},
            {"fragmentations", m.clear.fragmentations}, {"tp", m.clear.tp}, {"fp", m.clear.fp}, {"fn", m.clear.fn},
            {"gt", m.clear.gt}, {"hota", m.hota.hota}, {"deta", m.hota.deta}, {"assa", m.hota.assa}};
}

void print_table(const eval::TrackingMetrics& all, const std::map<ObjectClass, eval::TrackingMetrics>& per) {
    std::cout << "| class | HOTA | DetA | AssA | MOTA | MOTP | ID switches | fragmentations | GT |\n|---|---|---|---|---|---|---|---|---|\n";
    auto row = [](const std::string& name, const eval::TrackingMetrics& m) {
        std::cout << std::fixed << std::setprecision(3) << "| " << name << " | " << m.hota.hota << " | " << m.hota.deta << " | "
                  << m.hota.assa << " | " << m.clear.mota << " | " << m.clear.motp << " | " << m.clear.id_switches << " | "
                  << m.clear.fragmentations << " | " << m.clear.gt << " |\n";
    };
    for (const auto& [cls, m] : per) row(std::string(to_string(cls)), m);
    row("all", all);
}

}  // namespace

int run_eval_tracking(const EvalTrackingOptions& o) {
    std::vector<eval::TrackingFrame> gt, tracks;
    if (o.format == "kitti") {
        const auto gt_files = kitti_sequences(o.gt);
        std::uint32_t offset = 0;
        for (const auto& g : gt_files) {
            const fs::path t = fs::is_regular_file(o.tracks) ? fs::path(o.tracks) : fs::path(o.tracks) / g.filename();
            if (!fs::exists(t)) throw io::FileError(t.string(), "no tracks for ground-truth sequence " + g.filename().string());
            auto gf = kitti_frames(g, true), tf = kitti_frames(t, true);
            gf.resize(std::max(gf.size(), tf.size())), tf.resize(gf.size());
            for (auto* v : {&gf, &tf}) {
                for (auto& f : *v) for (auto& b : f) b.id += offset;  // ids unique across sequences
            }
            offset += 1000000u;
            gt.insert(gt.end(), gf.begin(), gf.end());
            tracks.insert(tracks.end(), tf.begin(), tf.end());
        }
    } else {
        const auto gt_files = io::frame_files(o.gt, "json");
        const auto tr_files = io::frame_files(o.tracks, "json");
        if (gt_files.size() != tr_files.size()) {
            throw io::FileError(o.tracks, "holds " + std::to_string(tr_files.size()) + " frames, the ground truth " + std::to_string(gt_files.size()));
        }
        auto frame = [](const fs::path& f) {
            eval::TrackingFrame out;
            for (const ObjectEstimate& e : io::read_object_frame(f)) out.push_back({e.id, e.cls, e.box_world});
            return out;
        };
        for (std::size_t k = 0; k < gt_files.size(); ++k) gt.push_back(frame(gt_files[k])), tracks.push_back(frame(tr_files[k]));
    }
    const auto all = eval::evaluate_tracking(gt, tracks);
    const auto per = eval::evaluate_tracking_per_class(gt, tracks);
    print_table(all, per);
    if (!o.out.empty()) {
        io::Json j = metrics_json(all);
        for (const auto& [cls, m] : per) j["per_class"][std::string(to_string(cls))] = metrics_json(m);
        io::write_json(o.out, j);
    }
    return 0;
}

int run_bench_track(const BenchTrackOptions& o) {
    eval::TrackBenchParams p;
    p.scenes = o.scenes;
    p.seed = o.seed;
    p.use_scan_occlusion = o.scan_occlusion;
    io::ProgressBar bar("bench track", static_cast<std::size_t>(p.scenes));
    const eval::TrackBenchResult r = eval::run_track_bench(p, [&](int done, int) { bar.update(static_cast<std::size_t>(done)); });
    bar.finish();
    io::Json j = metrics_json(r.overall);
    j["fps"] = r.fps;
    j["frames"] = r.frames;
    j["scenes"] = p.scenes;
    j["seed"] = p.seed;
    j["mean_detections_per_frame"] = r.mean_detections_per_frame;
    j["scan_occlusion"] = p.use_scan_occlusion;
    j["yaw_within_10deg_detections"] = r.yaw_within_10deg_detections;
    j["yaw_within_10deg_map"] = r.yaw_within_10deg_map;
    j["occlusion_gaps_up_to_2s"] = r.occlusion_gaps;
    j["occlusion_gaps_kept_id"] = r.occlusion_gaps_kept;
    j["false_positives"] = r.false_positives;
    j["false_positive_track_frames_in_map"] = r.false_positive_tracks_output;
    j["false_positive_tracks_after_3_frames"] = r.false_positive_tracks_lingering;
    j["rates"] = {{"miss", p.p_miss}, {"false_positive", p.false_positive_rate}, {"flip_90_each", p.p_flip_90}, {"flip_180", p.p_flip_180}};
    for (const auto& [cls, m] : r.per_class) j["per_class"][std::string(to_string(cls))] = metrics_json(m);
    fs::create_directories(o.out_dir);
    io::write_json(fs::path(o.out_dir) / "summary.json", j);
    print_table(r.overall, r.per_class);
    std::cout << std::setprecision(1) << "fps " << r.fps << ", yaw within 10 deg: detections " << 100 * r.yaw_within_10deg_detections
              << " %, map " << 100 * r.yaw_within_10deg_map << " %; wrote " << (fs::path(o.out_dir) / "summary.json").string() << "\n";
    return 0;
}

}  // namespace makeway::apps

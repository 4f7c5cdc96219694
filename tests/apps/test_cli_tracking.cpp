// End-to-end tests of `track` and `eval-tracking`: makeway JSON and KITTI, including KITTI as
// published data arrive (any class, DontCare, logits, empty sequences).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "../io/io_test_util.hpp"
#include "cli_test_util.hpp"
#include "io/json_io.hpp"
#include "io/pose_io.hpp"
#include "io/tracking_io.hpp"

namespace makeway {
namespace {

using testing_util::CliRun;
using testing_util::lines;
using testing_util::run_makeway;

TEST(Cli, TrackAndEvalTrackingInBothFormats) {
    const auto dir = testing_util::fresh_dir("track");
    std::ofstream(dir / "room.yaml")
        << "name: room\nfloor: {min_m: [-4.5, -2.5], max_m: [4.5, 2.5]}\n"
           "walls:\n  - {a_m: [-4.5, -2.5], b_m: [4.5, -2.5]}\n  - {a_m: [4.5, -2.5], b_m: [4.5, "
           "2.5]}\n"
           "  - {a_m: [4.5, 2.5], b_m: [-4.5, 2.5]}\n  - {a_m: [-4.5, 2.5], b_m: [-4.5, -2.5]}\n"
           "objects:\n  - {id: 1, class: chair, style: four_leg_chair, model_seed: 4, pose: {x_m: "
           "-1, y_m: 0.6, yaw_rad: 0.6}}\n"
           "  - {id: 2, class: table, style: rect_table, model_seed: 2, pose: {x_m: 1.5, y_m: "
           "-0.8, yaw_rad: 0.1}}\n"
           "  - {id: 3, class: chair, style: office_chair, model_seed: 1, pose: {x_m: 2.5, y_m: "
           "1.2, yaw_rad: -2.0}}\n"
           "start: {x_m: -3, y_m: -0.5, yaw_rad: 0}\nwaypoint: {x_m: -3, y_m: -0.5, yaw_rad: 0}\n"
           "goal: {x_m: -3, y_m: -0.5, yaw_rad: 0}\n";
    ASSERT_EQ(run_makeway("simulate --scene " + (dir / "room.yaml").string() +
                              " --frames 20 --out " + (dir / "sim").string(),
                          dir)
                  .exit_code,
              0);
    // A perfect detector: every ground-truth box in the sensor frame, one JSON per frame, and the
    // same as one KITTI detection file (camera frame) plus KITTI ground truth.
    const auto poses = io::read_tum(dir / "sim" / "poses_gt.txt");
    const auto gt_files = io::frame_files(dir / "sim" / "objects", "json");
    ASSERT_EQ(gt_files.size(), 20u);
    std::filesystem::create_directories(dir / "dets");
    std::vector<io::KittiTrackingRecord> kitti_dets, kitti_gt;
    for (std::size_t k = 0; k < gt_files.size(); ++k) {
        io::DetectionFrame f;
        f.stamp_s = poses[k].stamp_s;
        f.T_world_sensor = poses[k].T_world_sensor;
        for (const ObjectEstimate& o : io::read_object_frame(gt_files[k])) {
            Detection d;
            d.cls = o.cls;
            d.box_sensor = o.box_world.transformed(poses[k].T_world_sensor.inverse());
            d.class_probabilities = {o.cls == ObjectClass::kChair ? 0.9 : 0.1,
                                     o.cls == ObjectClass::kChair ? 0.1 : 0.9};
            d.score = 0.9;
            f.detections_sensor.push_back(d);
            kitti_dets.push_back(io::to_kitti(d.box_sensor, d.cls, static_cast<int>(k), -1, 0.9));
            kitti_gt.push_back(io::to_kitti(d.box_sensor, d.cls, static_cast<int>(k),
                                            static_cast<int>(o.id), std::nullopt));
        }
        io::write_json(dir / "dets" / gt_files[k].filename(), io::to_json(f));
    }
    io::write_kitti_tracking(dir / "kitti_dets" / "0000.txt", kitti_dets);
    io::write_kitti_tracking(dir / "kitti_gt" / "0000.txt", kitti_gt);

    CliRun r = run_makeway(
        "track --detections " + (dir / "dets").string() + " --out " + (dir / "tracks").string(),
        dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto last = io::read_object_frame(dir / "tracks" / gt_files.back().filename());
    ASSERT_EQ(last.size(), 3u);
    r = run_makeway("eval-tracking --gt " + (dir / "sim" / "objects").string() + " --tracks " +
                        (dir / "tracks").string() + " --out " + (dir / "m.json").string(),
                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const io::Json m = io::read_json(dir / "m.json");
    // Frame 0 is missed by design (objects enter the map on their second detection): MOTA = 1 -
    // 3/60.
    EXPECT_NEAR(m["mota"].get<double>(), 1.0 - 3.0 / 60.0, 1e-9);
    EXPECT_EQ(m["id_switches"].get<int>(), 0);
    EXPECT_GT(m["per_class"]["table"]["hota"].get<double>(), 0.9);

    r = run_makeway("track --format kitti --detections " + (dir / "kitti_dets").string() +
                        " --out " + (dir / "kitti_tracks").string(),
                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = run_makeway("eval-tracking --format kitti --gt " + (dir / "kitti_gt").string() +
                        " --tracks " + (dir / "kitti_tracks").string() + " --out " +
                        (dir / "mk.json").string(),
                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const io::Json mk = io::read_json(dir / "mk.json");
    // KITTI output starts at a confirmed track's first detection (as AB3DMOT's): frame 0 is there.
    EXPECT_NEAR(mk["classes"]["chair"]["all_boxes"]["mota"].get<double>(), 1.0, 1e-9);
    EXPECT_NEAR(mk["classes"]["table"]["all_boxes"]["mota"].get<double>(), 1.0, 1e-9);
    // --no-backfill: from the frame that confirms it; frame 0 missed: two chairs of 40 boxes, one
    // table of 20.
    r = run_makeway("track --format kitti --no-backfill --detections " +
                        (dir / "kitti_dets").string() + " --out " + (dir / "kitti_nb").string(),
                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = run_makeway("eval-tracking --format kitti --gt " + (dir / "kitti_gt").string() +
                        " --tracks " + (dir / "kitti_nb").string() + " --out " +
                        (dir / "mk_nb.json").string(),
                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const io::Json mk_nb = io::read_json(dir / "mk_nb.json");
    EXPECT_NEAR(mk_nb["classes"]["chair"]["all_boxes"]["mota"].get<double>(), 1.0 - 2.0 / 40.0,
                1e-9);
    EXPECT_NEAR(mk_nb["classes"]["table"]["all_boxes"]["mota"].get<double>(), 1.0 - 1.0 / 20.0,
                1e-9);

    // Bad input: one line naming the file, exit 2, nothing written.
    std::filesystem::copy(dir / "dets", dir / "dets_bad");
    std::ofstream(dir / "dets_bad" / gt_files[5].filename())
        << "{\"detections\": [{\"class\": \"sofa\"}]}";
    r = run_makeway(
        "track --detections " + (dir / "dets_bad").string() + " --out " + (dir / "t2").string(),
        dir);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find((dir / "dets_bad" / gt_files[5].filename()).string() +
                         ": detection 0: 'class' must be chair or table"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "t2"));
    r = run_makeway("eval-tracking --gt " + (dir / "sim" / "objects").string() + " --tracks " +
                        (dir / "dets").string(),
                    dir);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("expected {\"objects\": [...]}"), std::string::npos) << r.err;
    EXPECT_EQ(run_makeway("track --format csv --detections x --out y", dir).exit_code, 2);
}

// KITTI as published data arrive: any class names, DontCare lines (size -1), raw logit scores,
// sequences without objects, 2D boxes the devkit needs. Camera frame: x right, y down, z forward.
std::string kitti_line(int frame, int id, const std::string& type, double x, double z, double score,
                       std::array<int, 4> bbox = {600, 150, 700, 250}) {
    std::ostringstream s;
    s << frame << " " << id << " " << type << " 0 0 -1.57 " << bbox[0] << " " << bbox[1] << " "
      << bbox[2] << " " << bbox[3] << " 1.5 1.6 3.9 " << x << " 1.7 " << z << " -1.57";
    if (!std::isnan(score)) s << " " << score;
    return s.str() + "\n";
}

TEST(Cli, TrackAndEvaluateKittiAsPublishedDataArrive) {
    const auto dir = testing_util::fresh_dir("kitti");
    std::filesystem::create_directories(dir / "dets");
    std::filesystem::create_directories(dir / "gt");
    const double nan = std::nan("");
    std::string dets, gt;
    for (int f = 0; f < 30; ++f) {
        // Car 1 ahead at 20 m the whole time; car 2 at 50 m, seen for the first 10 frames only
        // (then it is never detected again: before, its track drove on for good); a van; a cyclist.
        dets += kitti_line(f, -1, "Car", 2.0, 20.0, 4.2);  // logits, as PointRCNN writes them
        gt += kitti_line(f, 1, "Car", 2.0, 20.0, nan);
        if (f < 10)
            dets += kitti_line(f, -1, "Car", -6.0, 50.0 - 0.5 * f, 2.5),
                gt += kitti_line(f, 2, "Car", -6.0, 50.0 - 0.5 * f, nan);
        dets += kitti_line(f, -1, "Cyclist", 8.0, 12.0 + 0.2 * f, 1.1);
        gt += kitti_line(f, 4, "Cyclist", 8.0, 12.0 + 0.2 * f, nan);
        gt += kitti_line(f, 3, "Van", -3.0, 30.0, nan);
        dets += kitti_line(f, -1, "Car", -3.0, 30.0, -0.5);  // a detection of the van, as "Car"
        gt += std::to_string(f) +
              " -1 DontCare -1 -1 -10 100 120 200 200 -1 -1 -1 -1000 -1000 -1000 -10\n";
        dets += kitti_line(f, -1, "Car", -12.0, 25.0, 0.8,
                           {110, 130, 190, 190});  // inside the DontCare area
    }
    std::ofstream(dir / "dets" / "0000.txt") << dets;
    std::ofstream(dir / "gt" / "0000.txt") << gt;
    std::ofstream(dir / "dets" / "0001.txt");  // a sequence without detections
    std::ofstream(dir / "gt" / "0001.txt");

    // none refuses logits with one line naming the file; auto reads them through the sigmoid.
    CliRun r = run_makeway("track --format kitti --score-transform none --detections " +
                               (dir / "dets").string() + " --out " + (dir / "bad").string(),
                           dir);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("0000.txt: score 4.2 is not in [0, 1]"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "bad"));
    r = run_makeway("track --format kitti --detections " + (dir / "dets").string() + " --out " +
                        (dir / "tracks").string(),
                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("read as logits"), std::string::npos) << r.out;
    const auto tracks = io::read_kitti_tracking(dir / "tracks" / "0000.txt");
    EXPECT_TRUE(std::filesystem::exists(dir / "tracks" / "0001.txt"));
    EXPECT_TRUE(io::read_kitti_tracking(dir / "tracks" / "0001.txt").empty());
    std::set<std::string> types;
    std::set<double> scores;
    // Car 2's first and last frame out: boxes only where a detection updated them (no coasting).
    const auto far_frames = [](const std::vector<io::KittiTrackingRecord>& records) {
        int first = 1000, last = -1;
        for (const auto& t : records) {
            if (t.location_cam_m.x() < -5.0 && t.location_cam_m.x() > -7.0)
                first = std::min(first, t.frame), last = std::max(last, t.frame);
        }
        return std::pair{first, last};
    };
    for (const auto& t : tracks) {
        types.insert(t.type);
        EXPECT_GE(t.bbox_px[0], 0.0);  // the 2D box of its detection, not -1
        scores.insert(*t.score);  // the matched detection's, as given (--output-score detection)
        EXPECT_LT(t.location_cam_m.z(), 80.0);
    }
    EXPECT_EQ(types, (std::set<std::string>{"Car", "Cyclist"}));
    EXPECT_EQ(scores, (std::set<double>{4.2, 2.5, 1.1, -0.5, 0.8}));
    EXPECT_EQ(far_frames(tracks), (std::pair{0, 9}));
    // --coasting: confirmed tracks also in frames without a detection, gone within max_misses (3)
    // unexplained misses of the last detection at frame 9 (the van hides it for a frame on the way,
    // which is not held against it); --output-score existence: the fused existence, in [0, 1].
    r = run_makeway("track --format kitti --coasting --output-score existence --detections " +
                        (dir / "dets").string() + " --out " + (dir / "coast").string(),
                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto coasting = io::read_kitti_tracking(dir / "coast" / "0000.txt");
    EXPECT_GE(far_frames(coasting).second, 10);
    EXPECT_LE(far_frames(coasting).second, 13);
    for (const auto& t : coasting) EXPECT_TRUE(*t.score > 0.0 && *t.score <= 1.0) << *t.score;
    const io::Json summary = io::read_json(dir / "tracks" / "summary.json");
    EXPECT_EQ(summary["frames"].get<int>(), 30);
    EXPECT_GT(summary["frames_per_second"].get<double>(), 0.0);
    EXPECT_EQ(summary["tracker"]["Car"]["score_transform"].get<std::string>(),
              "sigmoid");  // the settings per type
    EXPECT_EQ(summary["tracker"]["Cyclist"]["min_hits"].get<int>(), 3);
    EXPECT_NE(r.out.find("frames per second"), std::string::npos);

    // --classes and --range select what is tracked.
    r = run_makeway("track --format kitti --classes car --range 40 --detections " +
                        (dir / "dets").string() + " --out " + (dir / "near").string(),
                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const auto& t : io::read_kitti_tracking(dir / "near" / "0000.txt")) {
        EXPECT_EQ(t.type, "Car");
        EXPECT_LT(t.location_cam_m.z(), 40.0);
    }

    // The protocol: the van's track and the one in the DontCare area are ignored; the empty
    // sequence is read; Car and Cyclist are scored.
    r = run_makeway("eval-tracking --format kitti --gt " + (dir / "gt").string() + " --tracks " +
                        (dir / "tracks").string() + " --out " + (dir / "m.json").string(),
                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const io::Json m = io::read_json(dir / "m.json");
    const io::Json& car = m["classes"]["car"]["all_boxes"];
    EXPECT_EQ(car["fp"].get<int>(), 0)
        << car.dump();  // the van's and the DontCare area's tracks ignored
    EXPECT_EQ(car["id_switches"].get<int>(), 0);
    EXPECT_GT(car["ignored_tracker"].get<int>(), 0);
    EXPECT_GT(car["ignored_tp"].get<int>(), 0);  // the van
    EXPECT_GT(m["classes"]["car"]["samota"].get<double>(), 0.8);
    EXPECT_TRUE(m["classes"].contains("cyclist"));
    // The official script's score handling: said in the output and the JSON.
    r = run_makeway("eval-tracking --format kitti --devkit-rounding --gt " + (dir / "gt").string() +
                        " --tracks " + (dir / "tracks").string() + " --out " +
                        (dir / "md.json").string(),
                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("--devkit-rounding"), std::string::npos) << r.out;
    const io::Json md = io::read_json(dir / "md.json");
    EXPECT_TRUE(md["protocol"]["devkit_rounding"].get<bool>());
    EXPECT_EQ(md["classes"]["car"]["all_boxes"]["tp"].get<int>(),
              car["tp"].get<int>());  // the first pass keeps every box
}

// Coasting per KITTI type: a pedestrian's predicted box goes out for one frame after its last
// detection by default (its preset), a car's for none; --no-coasting and --coasting with
// --coasting-frames override every type.
TEST(Cli, TrackKittiCoastsPedestriansOneFrameByDefault) {
    const auto dir = testing_util::fresh_dir("kitti_coast");
    std::filesystem::create_directories(dir / "dets");
    std::string dets;
    for (int f = 0; f < 30; ++f) {
        dets += kitti_line(f, -1, "Car", 2.0, 20.0, 4.2);  // seen throughout: the sequence goes on
        if (f <= 14)
            dets += kitti_line(f, -1, "Car", -6.0, 40.0, 3.0) +
                    kitti_line(f, -1, "Pedestrian", 5.0, 12.0, 1.5);
    }
    std::ofstream(dir / "dets" / "0000.txt") << dets;
    const auto last_frame = [&](const std::string& options, const std::string& out,
                                const std::string& type, double x) {
        const CliRun r = run_makeway("track --format kitti " + options + " --detections " +
                                         (dir / "dets").string() + " --out " + (dir / out).string(),
                                     dir);
        EXPECT_EQ(r.exit_code, 0) << r.err;
        int last = -1;
        for (const auto& t : io::read_kitti_tracking(dir / out / "0000.txt")) {
            if (t.type == type && std::abs(t.location_cam_m.x() - x) < 1.0)
                last = std::max(last, t.frame);
        }
        return last;
    };
    EXPECT_EQ(last_frame("", "preset", "Pedestrian", 5.0), 15);
    EXPECT_EQ(last_frame("", "preset", "Car", -6.0), 14);
    const io::Json summary = io::read_json(dir / "preset" / "summary.json");
    EXPECT_EQ(summary["coasting_frames_per_type"]["Pedestrian"].get<int>(), 1);
    EXPECT_EQ(summary["coasting_frames_per_type"]["Car"].get<int>(), -1);
    EXPECT_EQ(last_frame("--no-coasting", "none", "Pedestrian", 5.0), 14);
    EXPECT_EQ(last_frame("--coasting --coasting-frames 2", "two", "Pedestrian", 5.0), 16);
    EXPECT_EQ(last_frame("--coasting --coasting-frames 2", "two", "Car", -6.0), 16);
    for (const char* bad : {"--coasting --no-coasting",
                            "--coasting-frames 2"}) {  // contradictory; frames without coasting
        const CliRun r = run_makeway(std::string("track --format kitti ") + bad + " --detections " +
                                         (dir / "dets").string() + " --out " + (dir / "x").string(),
                                     dir);
        EXPECT_EQ(r.exit_code, 2) << bad;
        EXPECT_FALSE(std::filesystem::exists(dir / "x")) << bad;
    }
}

}  // namespace
}  // namespace makeway

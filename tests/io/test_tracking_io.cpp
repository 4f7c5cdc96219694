#include <gtest/gtest.h>

#include <fstream>

#include "io/error.hpp"
#include "io/tracking_io.hpp"
#include "io_test_util.hpp"
#include "makeway/common/angles.hpp"

namespace makeway::io {
namespace {

TEST(KittiTracking, RoundTripsRecordsAndBoxes) {
    const OrientedBox chair{{2.5, -1.0, 0.45}, {0.55, 0.5, 0.9}, 0.7};
    const OrientedBox table{{4.0, 2.0, 0.375}, {1.6, 0.8, 0.75}, -2.9};
    std::vector<KittiTrackingRecord> recs{to_kitti(chair, ObjectClass::kChair, 0, 3, 0.8),
                                          to_kitti(table, ObjectClass::kTable, 1, 7, std::nullopt),
                                          to_kitti(chair, ObjectClass::kChair, 2, -1, 0.5)};
    const auto dir = testing_util::fresh_dir("kitti_tracking");
    write_kitti_tracking(dir / "0000.txt", recs);
    const auto back = read_kitti_tracking(dir / "0000.txt");
    ASSERT_EQ(back.size(), 3u);
    EXPECT_EQ(back[0].track_id, 3);
    EXPECT_EQ(back[2].track_id, -1);  // a detection line
    EXPECT_EQ(back[1].type, "Table");
    EXPECT_FALSE(back[1].score.has_value());
    EXPECT_DOUBLE_EQ(*back[0].score, 0.8);
    for (std::size_t i = 0; i < 3; ++i) {
        const OrientedBox want = i == 1 ? table : chair;
        const OrientedBox got = box_from_kitti(back[i]);
        EXPECT_LT((got.centre_m - want.centre_m).norm(), 1e-12);
        EXPECT_LT((got.size_m - want.size_m).norm(), 1e-12);
        EXPECT_LT(std::abs(angle_diff(got.yaw_rad, want.yaw_rad)), 1e-12);
    }
    // KITTI's camera convention: z forward, y down, location at the bottom, ry = -yaw - pi/2.
    EXPECT_DOUBLE_EQ(recs[0].location_cam_m.z(), 2.5);
    EXPECT_DOUBLE_EQ(recs[0].location_cam_m.x(), 1.0);
    EXPECT_NEAR(recs[0].location_cam_m.y(), 0.0, 1e-12);
    EXPECT_NEAR(recs[0].rotation_y_rad, -0.7 - kPi / 2, 1e-12);
}

TEST(KittiTracking, MalformedLinesNameTheFileAndLine) {
    const auto dir = testing_util::fresh_dir("kitti_tracking_bad");
    std::ofstream(dir / "a.txt")
        << "0 1 Chair 0 0 0 0 0 0 0 0.9 0.5 0.5 1 0.45 2 0.1\n0 2 Chair 0 0 0\n";
    std::ofstream(dir / "b.txt") << "0 1 Chair 0 0 0 0 0 0 0 0.9 nan 0.5 1 0.45 2 0.1\n";
    std::ofstream(dir / "c.txt") << "0 1 Chair 0 0 0 0 0 0 0 0.9 0 0.5 1 0.45 2 0.1\n";
    for (const auto& [file, what] : std::vector<std::pair<std::string, std::string>>{
             {"a.txt", "line 2: expected 17 or 18 fields"},
             {"b.txt", "line 1: value is NaN or infinite"},
             {"c.txt", "line 1: box dimensions"}}) {
        try {
            read_kitti_tracking(dir / file);
            ADD_FAILURE() << file;
        } catch (const FileError& e) {
            EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
        }
    }
    EXPECT_EQ(class_of_kitti_type("CHAIR"), ObjectClass::kChair);
    // Published KITTI labels: DontCare regions have no 3D box (size -1); a sequence may be empty.
    std::ofstream(dir / "labels.txt")
        << "0 -1 DontCare -1 -1 -10 219.31 188.49 245.50 218.56 -1 -1 -1 -1000 -1000 -1000 -10\n"
           "0 0 Van 0 0 -1.79 296.74 161.75 455.22 292.50 2.00 1.82 4.43 -4.55 1.71 13.41 -2.11\n";
    const auto labels = read_kitti_tracking(dir / "labels.txt");
    ASSERT_EQ(labels.size(), 2u);
    EXPECT_TRUE(labels[0].is_dont_care());
    EXPECT_EQ(labels[0].track_id, -1);
    EXPECT_DOUBLE_EQ(labels[0].bbox_px[2], 245.50);
    EXPECT_FALSE(labels[1].is_dont_care());
    std::ofstream(dir / "empty.txt");
    EXPECT_TRUE(read_kitti_tracking(dir / "empty.txt").empty());
    EXPECT_FALSE(class_of_kitti_type("Car").has_value());
}

// AB3DMOT's detection files (how PointRCNN's published detections arrive): comma-separated, the
// type as a number, the score a raw logit before h w l.
TEST(KittiTracking, ReadsAb3dmotDetectionFiles) {
    const auto dir = testing_util::fresh_dir("kitti_ab3dmot");
    std::ofstream(dir / "0000.txt")
        << "0,2,296.7,161.8,455.2,292.5,9.4146,2.00,1.82,4.43,-4.55,1.71,13.41,-2.11,-1.79\n"
           "3,1,10,20,30,60,-0.25,1.7,0.6,0.8,1.0,1.6,8.0,0.1,0.0\n";
    const auto d = read_kitti_tracking(dir / "0000.txt");
    ASSERT_EQ(d.size(), 2u);
    EXPECT_EQ(d[0].type, "Car");
    EXPECT_EQ(d[0].track_id, -1);
    EXPECT_DOUBLE_EQ(*d[0].score, 9.4146);
    EXPECT_DOUBLE_EQ(d[0].l_m, 4.43);
    EXPECT_DOUBLE_EQ(d[0].location_cam_m.z(), 13.41);
    EXPECT_DOUBLE_EQ(d[0].rotation_y_rad, -2.11);
    EXPECT_DOUBLE_EQ(d[0].alpha, -1.79);
    EXPECT_DOUBLE_EQ(d[0].bbox_px[3], 292.5);
    EXPECT_EQ(d[1].frame, 3);
    EXPECT_EQ(d[1].type, "Pedestrian");
    EXPECT_DOUBLE_EQ(*d[1].score, -0.25);
    std::ofstream(dir / "bad.txt") << "0,4,1,2,3,4,0.5,1,1,1,0,0,5,0,0\n0,2,1,2\n";
    try {
        read_kitti_tracking(dir / "bad.txt");
        ADD_FAILURE();
    } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find(
                      "bad.txt: line 1: type 4 is not 1 (Pedestrian), 2 (Car) or 3 (Cyclist)"),
                  std::string::npos)
            << e.what();
    }
    std::ofstream(dir / "short.txt") << "0,2,1,2\n";
    EXPECT_THROW(read_kitti_tracking(dir / "short.txt"), FileError);
}

TEST(DetectionFrames, RoundTripAndRejectBadFields) {
    const auto dir = testing_util::fresh_dir("det_frames");
    DetectionFrame f;
    f.stamp_s = 1.5;
    f.T_world_sensor = make_T_xyz_yaw({1, 2, 0.45}, 0.3);
    Detection d;
    d.box_sensor = {{1, 0, 0}, {0.5, 0.5, 0.9}, 0.2};
    d.class_probabilities = {0.7, 0.3};
    d.score = 0.6;
    f.detections_sensor = {d};
    write_json(dir / "000000.json", to_json(f));
    const DetectionFrame g = read_detection_frame(dir / "000000.json");
    EXPECT_DOUBLE_EQ(g.stamp_s, 1.5);
    ASSERT_TRUE(g.T_world_sensor.has_value());
    EXPECT_TRUE(g.T_world_sensor->isApprox(*f.T_world_sensor, 1e-12));
    ASSERT_EQ(g.detections_sensor.size(), 1u);
    EXPECT_DOUBLE_EQ(g.detections_sensor[0].class_probabilities[1], 0.3);
    EXPECT_DOUBLE_EQ(g.detections_sensor[0].score, 0.6);
    std::ofstream(dir / "bad.json")
        << R"({"detections": [{"class": "chair", "box": {"centre_m": [0,0,0], "size_m": [1,1,1], "yaw_rad": 0}, "score": 2}]})";
    EXPECT_THROW(read_detection_frame(dir / "bad.json"), FileError);
    EXPECT_EQ(frame_files(dir, "json").size(), 2u);
    EXPECT_THROW(frame_files(dir / "nowhere", "json"), FileError);
}

}  // namespace
}  // namespace makeway::io

namespace makeway::io {
namespace {

TEST(DetectionFrames, ANumberThatOverflowsIsBadInputNotACrash) {
    // Found by fuzz_detection_json: nlohmann throws out_of_range, not parse_error, for it.
    EXPECT_THROW(parse_detection_frame("[{\"class\": \"chair\", \"score\": 5e555555555}]"),
                 FormatError);
    const auto dir = testing_util::fresh_dir("json_overflow");
    std::ofstream(dir / "f.json") << "{\"detections\": [], \"stamp_s\": 1e99999}";
    EXPECT_THROW(read_detection_frame(dir / "f.json"), FileError);
    EXPECT_THROW(read_json(dir / "f.json"), FileError);
}

}  // namespace
}  // namespace makeway::io

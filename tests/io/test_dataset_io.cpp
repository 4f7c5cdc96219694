#include <gtest/gtest.h>

#include <fstream>

#include "io/dataset_io.hpp"
#include "io/error.hpp"
#include "io/json_io.hpp"
#include "io_test_util.hpp"

namespace makeway::io {
namespace {

LabelledKeyframe keyframe(std::uint32_t sequence, double stamp_s) {
    LabelledKeyframe kf;
    kf.cloud_sensor.xyz = {{1.0f, 2.0f, 0.1f}, {3.0f, -1.0f, 0.4f}};
    kf.cloud_sensor.intensity = {5.0f, 9.0f};
    kf.objects.push_back(
        {7, ObjectClass::kChair, "office_chair", {{2.0, 1.0, -0.1}, {0.6, 0.6, 1.0}, 0.4}, 120});
    kf.unseen.push_back(
        {9, ObjectClass::kTable, "rect_table", {{-3.0, 4.0, -0.08}, {1.6, 0.8, 0.74}, -1.2}, 3});
    kf.sequence = sequence;
    kf.stamp_s = stamp_s;
    Isometry3 T = Isometry3::Identity();
    T.linear() =
        Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.1, 0.2, 1.0).normalized()))
            .toRotationMatrix();
    T.translation() = Eigen::Vector3d(4.0, -2.0, 0.45);
    kf.T_world_sensor = T;
    kf.ground_plane_sensor = Eigen::Vector4d(0.0, 0.6, 0.8, 0.45);
    return kf;
}

TEST(DatasetIo, RoundTripsLabelsPosesAndUnseenObjects) {
    const auto dir = testing_util::fresh_dir("dataset");
    write_labelled_keyframe(dir, 0, keyframe(0, 1.5));
    write_labelled_keyframe(dir, 1, keyframe(3, 2.5));
    const auto back = read_detection_dataset(dir);
    ASSERT_EQ(back.size(), 2u);
    const LabelledKeyframe want = keyframe(3, 2.5);
    const LabelledKeyframe& got = back[1];
    EXPECT_EQ(got.sequence, 3u);
    EXPECT_DOUBLE_EQ(got.stamp_s, 2.5);
    EXPECT_TRUE(got.T_world_sensor.isApprox(want.T_world_sensor, 1e-12));
    ASSERT_TRUE(got.ground_plane_sensor.has_value());  // what the detector levels with
    EXPECT_TRUE(got.ground_plane_sensor->isApprox(*want.ground_plane_sensor, 1e-12));
    ASSERT_EQ(got.cloud_sensor.size(), 2u);
    EXPECT_EQ(got.cloud_sensor.xyz[1], want.cloud_sensor.xyz[1]);
    ASSERT_EQ(got.objects.size(), 1u);
    ASSERT_EQ(got.unseen.size(), 1u);
    EXPECT_EQ(got.objects[0].id, 7u);
    EXPECT_EQ(got.objects[0].style, "office_chair");
    EXPECT_EQ(got.objects[0].points, 120u);
    EXPECT_EQ(got.unseen[0].id, 9u);
    EXPECT_EQ(got.unseen[0].cls, ObjectClass::kTable);
    EXPECT_DOUBLE_EQ(got.unseen[0].box_sensor.yaw_rad, -1.2);
}

TEST(DatasetIo, LabelsWithoutPosesLoadAsOneSequenceAndBadPosesNameTheFile) {
    const auto dir = testing_util::fresh_dir("dataset");
    write_labelled_keyframe(dir, 0, keyframe(0, 0.0));
    // Only "objects": older datasets and hand labels.
    Json label;
    label["objects"] = Json::array(
        {Json{{"class", "chair"}, {"box", to_json(OrientedBox{{1, 1, 0}, {0.5, 0.5, 0.9}, 0.0})}}});
    write_json(dir / "labels" / "000000.json", label);
    const auto plain = read_detection_dataset(dir);
    ASSERT_EQ(plain.size(), 1u);
    EXPECT_EQ(plain[0].sequence, 0u);
    EXPECT_TRUE(plain[0].T_world_sensor.isApprox(Isometry3::Identity()));
    EXPECT_TRUE(plain[0].unseen.empty());
    EXPECT_FALSE(plain[0].ground_plane_sensor.has_value());

    const char* bad[] = {
        R"({"objects": [], "T_world_sensor": {"t_m": [0, 0, 0], "q_wxyz": [2, 0, 0, 0]}})",
        R"({"objects": [], "T_world_sensor": {"t_m": [0, 0], "yaw_rad": 0}})",
        R"({"objects": [], "stamp_s": "soon"})",
        R"({"objects": [], "ground_plane": [0, 0, 1]})",
        R"({"objects": [], "ground_plane": [0, 0, 2, 0.4]})",
        R"({"objects": [], "unseen": [{"class": "sofa"}]})"};
    for (const char* text : bad) {
        std::ofstream(dir / "labels" / "000000.json") << text;
        try {
            (void)read_detection_dataset(dir);
            ADD_FAILURE() << "accepted " << text;
        } catch (const FileError& e) {
            EXPECT_NE(std::string(e.what()).find("000000.json"), std::string::npos) << e.what();
        }
    }
}

TEST(JsonIo, PosesReadBothForms) {
    const Isometry3 planar = pose_from_json(Json{{"t_m", {1, 2, 0.45}}, {"yaw_rad", 0.5}});
    EXPECT_TRUE(planar.isApprox(make_T_xyz_yaw({1, 2, 0.45}, 0.5), 1e-12));
    const Isometry3 T = keyframe(0, 0).T_world_sensor;
    EXPECT_TRUE(pose_from_json(pose_to_json(T)).isApprox(T, 1e-12));
    EXPECT_THROW(pose_from_json(Json{{"t_m", {1, 2, 0}}, {"q_wxyz", {1, 0, 0, NAN}}}), FormatError);
}

}  // namespace
}  // namespace makeway::io

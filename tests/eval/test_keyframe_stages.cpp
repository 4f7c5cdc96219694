#include <gtest/gtest.h>

#include "makeway/eval/keyframe_stages.hpp"

namespace makeway::eval {
namespace {

// A sensor driving along +x past a chair at world (3, 1) and a table at world (5, -2).
LabelledKeyframe drive_keyframe(std::uint32_t sequence, int k, bool chair_seen, bool table_seen) {
    LabelledKeyframe kf;
    kf.sequence = sequence;
    kf.stamp_s = 0.5 * k;
    kf.T_world_sensor = make_T_xyz_yaw({0.5 * k, 0.0, 0.45}, 0.0);
    const Isometry3 T_sensor_world = kf.T_world_sensor.inverse();
    const LabelledObject chair{
        1, ObjectClass::kChair, "office_chair",
        OrientedBox{{3.0, 1.0, 0.45}, {0.6, 0.6, 0.9}, 0.3}.transformed(T_sensor_world), 80};
    const LabelledObject table{
        2, ObjectClass::kTable, "rect_table",
        OrientedBox{{5.0, -2.0, 0.37}, {1.6, 0.8, 0.74}, 0.0}.transformed(T_sensor_world), 200};
    (chair_seen ? kf.objects : kf.unseen).push_back(chair);
    (table_seen ? kf.objects : kf.unseen).push_back(table);
    return kf;
}

TEST(KeyframeStages, MapGroundTruthKeepsWhatTheDriveHasSeen) {
    // Sequence 0: the table is hidden at first, then seen, then hidden again; the chair is seen,
    // then hidden. Sequence 1 starts over: nothing has been seen there.
    const std::vector<LabelledKeyframe> kfs{
        drive_keyframe(0, 0, true, false), drive_keyframe(0, 1, false, true),
        drive_keyframe(0, 2, false, false), drive_keyframe(1, 0, false, false)};
    const auto gt = map_ground_truth_of(kfs);
    ASSERT_EQ(gt.size(), 4u);
    EXPECT_EQ(gt[0].size(), 1u);  // the chair; the table never seen yet
    EXPECT_EQ(gt[1].size(), 2u);  // the table now, the chair remembered
    EXPECT_EQ(gt[2].size(), 2u);  // both remembered
    EXPECT_EQ(gt[3].size(), 0u);  // a new drive
    EXPECT_EQ(gt[1][0].cls, ObjectClass::kTable);
    EXPECT_FALSE(gt[0][0].pi_symmetric);
    EXPECT_TRUE(gt[1][0].pi_symmetric);
}

TEST(KeyframeStages, TrackedObjectsAppearOnceConfirmedInEachKeyframesFrame) {
    std::vector<LabelledKeyframe> kfs;
    for (int k = 0; k < 4; ++k) kfs.push_back(drive_keyframe(0, k, true, k != 3));
    kfs.push_back(drive_keyframe(1, 0, true, true));
    std::vector<std::vector<Detection>> dets;
    for (const LabelledKeyframe& kf : kfs) {
        std::vector<Detection> d;
        for (const LabelledObject& o : kf.objects) {
            Detection x;
            x.box_sensor = o.box_sensor;
            x.cls = o.cls;
            x.class_probabilities.fill(0.0);
            x.class_probabilities[static_cast<std::size_t>(o.cls)] = 1.0;
            x.score = 0.9;
            d.push_back(x);
        }
        dets.push_back(d);
    }
    const auto tracked = track_keyframes(kfs, dets, {}, 8.0);
    ASSERT_EQ(tracked.size(), 5u);
    EXPECT_TRUE(tracked[0].empty());  // one hit: not confirmed yet
    ASSERT_EQ(tracked[1].size(), 2u);
    ASSERT_EQ(tracked[3].size(), 2u);  // the table is missed once but kept
    EXPECT_TRUE(tracked[4].empty());   // a new drive starts a new map
    const auto gt = map_ground_truth_of(kfs);
    for (std::size_t k = 1; k < 4; ++k) {
        const DetectionMetrics m = evaluate_detections({tracked[k]}, {gt[k]});
        EXPECT_DOUBLE_EQ(m.mar_50, 1.0)
            << "keyframe " << k;  // boxes land in the keyframe's sensor frame
    }
    // Objects beyond the labelling range are left out, as the ground truth leaves them out.
    const auto near = track_keyframes(kfs, dets, {}, 3.0);
    for (const Detection& d : near[1]) EXPECT_LE(std::abs(d.box_sensor.centre_m.x()), 3.0);
    EXPECT_LT(near[1].size(), tracked[1].size());
}

}  // namespace
}  // namespace makeway::eval

#include <gtest/gtest.h>

#include "makeway/common/angles.hpp"
#include "makeway/eval/detection_metrics.hpp"

namespace makeway::eval {
namespace {

Detection det(double x, double score, ObjectClass cls = ObjectClass::kChair, double yaw = 0.0) {
    Detection d;
    d.box_sensor = {{x, 0.0, 0.5}, {1.0, 1.0, 1.0}, yaw};
    d.score = score;
    d.cls = cls;
    return d;
}

LabelledBox gt(double x, ObjectClass cls = ObjectClass::kChair) {
    return {cls, {{x, 0.0, 0.5}, {1.0, 1.0, 1.0}, 0.0}};
}

TEST(DetectionMetrics, AveragePrecisionByHand) {
    // TP, FP, TP over 2 positives: precision 1, 1/2, 2/3 at recall 1/2, 1/2, 1; envelope 1, 2/3,
    // 2/3.
    EXPECT_NEAR(average_precision({true, false, true}, 2), 0.5 * 1.0 + 0.5 * (2.0 / 3.0), 1e-12);
    EXPECT_DOUBLE_EQ(average_precision({true, true}, 2), 1.0);
    EXPECT_DOUBLE_EQ(average_precision({false, true}, 1), 0.5);
    EXPECT_DOUBLE_EQ(average_precision({}, 3), 0.0);
}

TEST(DetectionMetrics, MatchesAtBothThresholdsAndScoresYaw) {
    // Frame 0: a perfect chair (flipped by pi), a chair shifted 0.4 m (IoU 0.6/1.4 = 0.43: a hit at
    // 0.25 only), a false chair; frame 1: a table found, a table missed.
    const std::vector<std::vector<Detection>> dets{
        {det(0, 0.9, ObjectClass::kChair, kPi), det(5.4, 0.8), det(10, 0.7)},
        {det(20, 0.6, ObjectClass::kTable)}};
    const std::vector<std::vector<LabelledBox>> truth{
        {gt(0), gt(5)}, {gt(20, ObjectClass::kTable), gt(30, ObjectClass::kTable)}};
    const DetectionMetrics m = evaluate_detections(dets, truth);
    const auto& chair = m.per_class.at(ObjectClass::kChair);
    EXPECT_DOUBLE_EQ(chair.ap_25, 1.0);  // TP, TP, FP
    EXPECT_DOUBLE_EQ(chair.ar_25, 1.0);
    EXPECT_DOUBLE_EQ(chair.ap_50, 0.5);  // TP, FP, FP
    EXPECT_DOUBLE_EQ(chair.ar_50, 0.5);
    EXPECT_DOUBLE_EQ(chair.yaw_within_10deg, 0.5);  // the flipped one is wrong
    const auto& table = m.per_class.at(ObjectClass::kTable);
    EXPECT_DOUBLE_EQ(table.ap_25, 0.5);
    EXPECT_DOUBLE_EQ(table.ar_50, 0.5);
    EXPECT_DOUBLE_EQ(m.map_25, 0.75);
    EXPECT_DOUBLE_EQ(m.map_50, 0.5);
    // A duplicate of a matched box is a false positive.
    const DetectionMetrics dup = evaluate_detections({{det(0, 0.9), det(0.01, 0.8)}}, {{gt(0)}});
    EXPECT_DOUBLE_EQ(dup.per_class.at(ObjectClass::kChair).ap_50, 1.0);
    EXPECT_EQ(dup.per_class.at(ObjectClass::kChair).detections, 2u);
}

}  // namespace
}  // namespace makeway::eval

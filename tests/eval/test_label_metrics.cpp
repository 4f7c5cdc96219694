// The auto-label benchmark's metrics on known answers: class IoU from a confusion matrix, panoptic
// quality of constructed instance segmentations.
#include <gtest/gtest.h>

#include "makeway/eval/label_bench.hpp"

namespace makeway::eval {
namespace {

TEST(LabelMetrics, ClassIouFromConfusion) {
    std::array<std::array<std::size_t, labelling::kNumPointClasses>, labelling::kNumPointClasses>
        c{};
    c[0][0] = 8;  // ground right 8, 2 called permanent
    c[0][1] = 2;
    c[1][1] = 10;
    c[2][2] = 6;  // movable right 6, 3 called dynamic, 1 permanent called movable
    c[2][3] = 3;
    c[1][2] = 1;
    const auto iou = class_iou(c);
    EXPECT_DOUBLE_EQ(iou[0], 8.0 / 10.0);
    EXPECT_DOUBLE_EQ(iou[1], 10.0 / 13.0);  // 10 / (10 + 2 fp + 1 fn)
    EXPECT_DOUBLE_EQ(iou[2], 6.0 / 10.0);   // 6 / (6 + 1 fp + 3 fn)
    EXPECT_DOUBLE_EQ(iou[3], 0.0);          // 3 predicted, none true
}

TEST(LabelMetrics, PanopticQualityOfConstructedSegments) {
    // Truth: instance 1 (10 points), instance 2 (10 points), instance 3 (4 points: too small to
    // count).
    std::vector<std::uint32_t> truth, pred;
    for (int i = 0; i < 10; ++i) truth.push_back(1), pred.push_back(7);  // a perfect match
    for (int i = 0; i < 10; ++i)
        truth.push_back(2), pred.push_back(i < 6 ? 8 : 0);  // 6 of 10: IoU 0.6
    for (int i = 0; i < 4; ++i) truth.push_back(3), pred.push_back(0);
    for (int i = 0; i < 10; ++i) truth.push_back(0), pred.push_back(9);  // a false segment
    PanopticQuality pq;
    add_panoptic(truth, pred, 5, pq);
    EXPECT_EQ(pq.tp, 2u);
    EXPECT_EQ(pq.fp, 1u);
    EXPECT_EQ(pq.fn, 0u);
    EXPECT_DOUBLE_EQ(pq.sq(), (1.0 + 0.6) / 2.0);
    EXPECT_DOUBLE_EQ(pq.rq(), 2.0 / 2.5);
    EXPECT_DOUBLE_EQ(pq.pq(), 1.6 / 2.5);
    // A segment at IoU 0.5 is not a match (strictly above, as Kirillov et al.): both unmatched.
    PanopticQuality half;
    add_panoptic({4, 4, 4, 4, 0, 0, 0, 0}, {5, 5, 5, 5, 5, 5, 5, 5}, 1, half);
    EXPECT_EQ(half.tp, 0u);
    EXPECT_EQ(half.fp, 1u);
    EXPECT_EQ(half.fn, 1u);
    EXPECT_EQ(PanopticQuality{}.pq(), 0.0);
}

}  // namespace
}  // namespace makeway::eval

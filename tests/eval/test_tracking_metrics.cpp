#include <gtest/gtest.h>

#include <cmath>

#include "makeway/eval/tracking_metrics.hpp"

namespace makeway::eval {
namespace {

TrackedBox at(std::uint32_t id, double x, ObjectClass cls = ObjectClass::kChair) {
    return {id, cls, OrientedBox{{x, 0.0, 0.5}, {1.0, 1.0, 1.0}, 0.0}};
}

TEST(TrackingMetrics, PerfectTrackingScoresOne) {
    const std::vector<TrackingFrame> gt{{at(1, 0)}, {at(1, 0.1)}, {at(1, 0.2)}};
    const std::vector<TrackingFrame> tr{{at(7, 0)}, {at(7, 0.1)}, {at(7, 0.2)}};
    const TrackingMetrics m = evaluate_tracking(gt, tr);
    EXPECT_DOUBLE_EQ(m.clear.mota, 1.0);
    EXPECT_NEAR(m.clear.motp, 1.0, 1e-12);
    EXPECT_NEAR(m.hota.hota, 1.0, 1e-12);
    EXPECT_NEAR(m.hota.deta, 1.0, 1e-12);
    EXPECT_NEAR(m.hota.assa, 1.0, 1e-12);
}

TEST(TrackingMetrics, AnIdSwitchHalvesAssociation) {
    // One object, 4 frames; the tracker changes its id half way.
    const std::vector<TrackingFrame> gt{{at(1, 0)}, {at(1, 0)}, {at(1, 0)}, {at(1, 0)}};
    const std::vector<TrackingFrame> tr{{at(10, 0)}, {at(10, 0)}, {at(11, 0)}, {at(11, 0)}};
    const TrackingMetrics m = evaluate_tracking(gt, tr);
    EXPECT_EQ(m.clear.id_switches, 1u);
    EXPECT_DOUBLE_EQ(m.clear.mota, 0.75);  // 1 - 1/4
    // HOTA by hand: DetA = 4/4; each of the two pairs has A = 2/(4+2-2) = 0.5; AssA =
    // (2*0.5+2*0.5)/4.
    EXPECT_NEAR(m.hota.deta, 1.0, 1e-12);
    EXPECT_NEAR(m.hota.assa, 0.5, 1e-12);
    EXPECT_NEAR(m.hota.hota, std::sqrt(0.5), 1e-12);
}

TEST(TrackingMetrics, MissesAndFalsePositives) {
    // Frame 0 matched; frame 1: the object is missed and a track sits 5 m away.
    const std::vector<TrackingFrame> gt{{at(1, 0)}, {at(1, 0)}};
    const std::vector<TrackingFrame> tr{{at(3, 0)}, {at(4, 5)}};
    const TrackingMetrics m = evaluate_tracking(gt, tr);
    EXPECT_EQ(m.clear.tp, 1u);
    EXPECT_EQ(m.clear.fn, 1u);
    EXPECT_EQ(m.clear.fp, 1u);
    EXPECT_DOUBLE_EQ(m.clear.mota, 0.0);  // 1 - (1 + 1) / 2
    // DetA = 1 / (2 + 2 - 1); AssA = 1 * 1/(2 + 1 - 1) / 1 = 0.5.
    EXPECT_NEAR(m.hota.deta, 1.0 / 3.0, 1e-12);
    EXPECT_NEAR(m.hota.assa, 0.5, 1e-12);
    EXPECT_NEAR(m.hota.hota, std::sqrt(1.0 / 6.0), 1e-12);
}

TEST(TrackingMetrics, PartialOverlapCountsForAlphasUpToItsIou) {
    // Unit boxes shifted by 1/3: IoU = (2/3) / (4/3) = 0.5, a match for alpha 0.05 ... 0.5 (10 of
    // 19).
    const std::vector<TrackingFrame> gt{{at(1, 0)}};
    const std::vector<TrackingFrame> tr{{at(2, 1.0 / 3.0)}};
    const TrackingMetrics m = evaluate_tracking(gt, tr);
    EXPECT_NEAR(m.hota.hota, 10.0 / 19.0, 1e-9);
    EXPECT_NEAR(m.clear.motp, 0.5, 1e-9);
    EXPECT_DOUBLE_EQ(m.clear.mota, 1.0);
}

TEST(TrackingMetrics, FragmentationAndPerClass) {
    const std::vector<TrackingFrame> gt{{at(1, 0), at(2, 3, ObjectClass::kTable)},
                                        {at(1, 0), at(2, 3, ObjectClass::kTable)},
                                        {at(1, 0), at(2, 3, ObjectClass::kTable)}};
    const std::vector<TrackingFrame> tr{{at(5, 0), at(6, 3, ObjectClass::kTable)},
                                        {at(6, 3, ObjectClass::kTable)},
                                        {at(5, 0), at(6, 3, ObjectClass::kTable)}};
    const TrackingMetrics all = evaluate_tracking(gt, tr);
    EXPECT_EQ(all.clear.fragmentations, 1u);
    EXPECT_EQ(all.clear.id_switches, 0u);
    EXPECT_EQ(all.clear.fn, 1u);
    const auto per = evaluate_tracking_per_class(gt, tr);
    EXPECT_DOUBLE_EQ(per.at(ObjectClass::kTable).clear.mota, 1.0);
    EXPECT_NEAR(per.at(ObjectClass::kChair).clear.mota, 2.0 / 3.0, 1e-12);
    // Empty input: defined zeros.
    EXPECT_DOUBLE_EQ(evaluate_tracking({}, {}).hota.hota, 0.0);
}

}  // namespace
}  // namespace makeway::eval

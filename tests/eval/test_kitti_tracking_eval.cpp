// The KITTI tracking protocol on hand-computed cases: DontCare regions, neighbouring classes,
// truncated ground truth, id switches and fragmentations by the devkit's rules, and the
// score-threshold sweep behind sAMOTA / AMOTA / AMOTP.
#include <gtest/gtest.h>

#include "makeway/eval/kitti_tracking_eval.hpp"

namespace makeway::eval {
namespace {

KittiBox car(int id, double x, double y, std::array<double, 4> bbox = {100, 100, 200, 200},
             double score = 1.0, std::string type = "car") {
    KittiBox b;
    b.track_id = id;
    b.type = std::move(type);
    b.bbox_px = bbox;
    b.box = OrientedBox{{x, y, 0.75}, {4.0, 1.8, 1.5}, 0.0};
    b.score = score;
    return b;
}

KittiBox dont_care(std::array<double, 4> bbox) {
    KittiBox b;
    b.type = "dontcare";
    b.bbox_px = bbox;
    return b;
}

TEST(KittiEval, DontCareNeighboursAndTruncationAreIgnoredAsTheDevkitDoes) {
    // One frame. Ground truth: car 1 (clear), van 2, car 3 truncated (level 1), a DontCare area.
    // Tracker: a match for each of the three, one box inside the DontCare area, one box elsewhere
    // (50 px tall: a real false positive) and one only 20 px tall (too small: ignored).
    KittiBox truncated = car(3, 30, -5);
    truncated.truncation = 1;
    const KittiFrame g{car(1, 10, 0), car(2, 20, 5, {100, 100, 200, 200}, 1.0, "van"), truncated,
                       dont_care({500, 100, 600, 200})};
    const KittiFrame t{car(11, 10, 0),
                       car(12, 20, 5),
                       car(13, 30, -5),
                       car(14, 40, 10, {510, 110, 590, 190}),
                       car(15, 50, -10, {300, 100, 400, 150}),
                       car(16, 60, 10, {700, 100, 750, 120})};
    const KittiClear m = evaluate_kitti_at({{g}}, {{t}}, {}, -1e9);
    EXPECT_EQ(m.tp, 3u);               // the devkit's tp counts ignored true positives
    EXPECT_EQ(m.ignored_tp, 2u);       // the van and the truncated car
    EXPECT_EQ(m.ignored_tracker, 2u);  // in the DontCare area; too small
    EXPECT_EQ(m.fp, 1u);
    EXPECT_EQ(m.fn, 0u);
    EXPECT_EQ(m.gt, 1u);
    EXPECT_DOUBLE_EQ(m.mota, 0.0);  // 1 - (0 + 1 + 0) / 1
    EXPECT_NEAR(m.motp, 1.0, 1e-9);
    // Without the protocol's ignore rules the same boxes score 3 ground truth, 3 false positives.
    KittiEvalParams raw;
    raw.use_dont_care = false, raw.ignore_neighbours = false, raw.max_truncation = 2,
    raw.min_height_px = 0;
    const KittiClear r = evaluate_kitti_at({{g}}, {{t}}, raw, -1e9);
    EXPECT_EQ(r.gt, 2u);  // the van is no longer loaded for "car"
    EXPECT_EQ(r.fp, 4u);  // ... and the tracker's box on it is a false positive
}

TEST(KittiEval, IdSwitchesAndFragmentationsFollowTheDevkit) {
    // One car over six frames. Tracker ids: 5 5 6 6 - 6 (a switch at frame 2, a miss at frame 4).
    KittiSequence gt, tr;
    const std::vector<int> ids{5, 5, 6, 6, -1, 6};
    for (std::size_t k = 0; k < ids.size(); ++k) {
        gt.push_back({car(1, 10, 0)});
        tr.push_back(ids[k] < 0 ? KittiFrame{} : KittiFrame{car(ids[k], 10, 0)});
    }
    const KittiClear m = evaluate_kitti_at({gt}, {tr}, {}, -1e9);
    EXPECT_EQ(m.id_switches, 1u);
    // Fragmentations: the switch at frame 2, and the resumption after the miss at frame 5.
    EXPECT_EQ(m.fragmentations, 2u);
    EXPECT_EQ(m.tp, 5u);
    EXPECT_EQ(m.fn, 1u);
    EXPECT_NEAR(m.mota, 1.0 - 2.0 / 6.0, 1e-12);
    EXPECT_DOUBLE_EQ(m.mostly_tracked, 1.0);  // 5 of 6 frames > 80 %
}

TEST(KittiEval, ThresholdsFollowRecallStepsAndTheSweepAveragesThem) {
    // Hand-computed: four ground-truth boxes matched with scores 0.9, 0.8, 0.7, 0.6 and 4 steps:
    // recall 0.25 at each score; the zero-recall entry is dropped.
    const auto th = kitti_thresholds({0.6, 0.9, 0.7, 0.8}, 4, 4);
    ASSERT_EQ(th.size(), 3u);
    EXPECT_DOUBLE_EQ(th[0].first, 0.8);
    EXPECT_DOUBLE_EQ(th[0].second, 0.25);
    EXPECT_DOUBLE_EQ(th[2].first, 0.6);
    EXPECT_DOUBLE_EQ(th[2].second, 0.75);

    // A constructed sequence: four cars, each seen for one frame, tracked by four tracks of
    // scores 0.9, 0.8, 0.7, 0.6; and a false track (score 0.65) for one frame.
    KittiSequence gt, tr;
    const std::vector<double> scores{0.9, 0.8, 0.7, 0.6};
    for (std::size_t k = 0; k < 4; ++k) {
        gt.push_back({car(static_cast<int>(k + 1), 10.0 + 10 * k, 0)});
        tr.push_back(
            {car(static_cast<int>(k + 11), 10.0 + 10 * k, 0, {100, 100, 200, 200}, scores[k])});
    }
    tr[0].push_back(car(99, 15, 20, {300, 100, 400, 200}, 0.65));
    KittiEvalParams p;
    p.recall_steps = 4;
    const KittiEvalResult r = evaluate_kitti({gt}, {tr}, p);
    EXPECT_EQ(r.all.tp, 4u);
    EXPECT_EQ(r.all.fp, 1u);
    ASSERT_EQ(r.curve.size(), 3u);
    // Threshold 0.8 (recall step 0.25): 2 tp, 2 fn, 0 fp -> MOTA 0.5, sMOTA 1 - (2 -
    // 0.75*4)/(0.25*4) -> 1 (clamped).
    EXPECT_DOUBLE_EQ(r.curve[0].mota, 0.5);
    EXPECT_DOUBLE_EQ(r.curve[0].smota, 1.0);
    // Threshold 0.7 (0.5): 3 tp, 1 fn, 0 fp -> MOTA 0.75, sMOTA 1 - (1 - 2)/2 -> 1.
    EXPECT_DOUBLE_EQ(r.curve[1].mota, 0.75);
    // Threshold 0.6 (0.75): 4 tp, 1 fp -> MOTA 0.75, sMOTA 1 - (1 - 1)/3 = 1.
    EXPECT_DOUBLE_EQ(r.curve[2].mota, 0.75);
    EXPECT_DOUBLE_EQ(r.curve[2].smota, 1.0);
    EXPECT_DOUBLE_EQ(r.samota, 3.0 / 4.0);  // three steps of 1, the fourth (recall 1) never reached
    EXPECT_DOUBLE_EQ(r.amota, (0.5 + 0.75 + 0.75) / 4.0);
    EXPECT_NEAR(r.amotp, 3.0 / 4.0, 1e-9);
    EXPECT_DOUBLE_EQ(r.best.mota, 0.75);
}

TEST(KittiEval, TheFieldOfViewDropsBoxesBehindTheCamera) {
    const KittiFrame g{car(1, 10, 0), car(2, -10, 0)};
    const KittiFrame t{car(11, 10, 0), car(12, -10, 0), car(13, 0, 15, {300, 100, 400, 200})};
    KittiEvalParams p;
    EXPECT_EQ(evaluate_kitti_at({{g}}, {{t}}, p, -1e9).fp, 1u);
    EXPECT_EQ(evaluate_kitti_at({{g}}, {{t}}, p, -1e9).gt, 2u);
    p.fov_deg = 90.0;
    const KittiClear m = evaluate_kitti_at({{g}}, {{t}}, p, -1e9);
    EXPECT_EQ(m.gt, 1u);
    EXPECT_EQ(m.fp, 0u);
    EXPECT_DOUBLE_EQ(m.mota, 1.0);
}

// AB3DMOT's evaluate.py writes each track's mean score over its boxes and, at every later
// threshold, averages those means again. One car over 7 frames, one track scored 0.85 in each:
// its mean is 0.8499999999999999 (seven 0.85 summed in order, over 7), and the mean of seven of
// those is one ulp lower. Every threshold of the sweep is that first mean, so the script drops the
// track at each of them (sAMOTA 0); the clean arithmetic keeps it.
TEST(KittiEval, DevkitRoundingDropsATrackWhoseReaveragedScoreFallsUnderItsOwnMean) {
    KittiSequence gt, tr;
    for (int k = 0; k < 7; ++k) {
        gt.push_back({car(1, 10, 0)});
        tr.push_back({car(9, 10, 0, {100, 100, 200, 200}, 0.85)});
    }
    double first = 0.0, again = 0.0;
    for (int k = 0; k < 7; ++k) first += 0.85;
    first /= 7;
    for (int k = 0; k < 7; ++k) again += first;
    again /= 7;
    ASSERT_LT(again, first);  // the premise: the floating point the script does
    KittiEvalParams clean, devkit;
    devkit.devkit_rounding = true;
    const KittiEvalResult c = evaluate_kitti({gt}, {tr}, clean),
                          d = evaluate_kitti({gt}, {tr}, devkit);
    ASSERT_FALSE(c.curve.empty());
    ASSERT_EQ(c.curve.size(), d.curve.size());
    for (std::size_t i = 0; i < c.curve.size(); ++i) {
        EXPECT_EQ(c.curve[i].threshold, first);
        EXPECT_EQ(d.curve[i].threshold, first);
        EXPECT_EQ(c.curve[i].tp, 7u);
        EXPECT_EQ(d.curve[i].tp, 0u);  // dropped: its score is now `again` < threshold
        EXPECT_EQ(d.curve[i].fn, 7u);
    }
    // Seven boxes reach 6 of the 40 recall steps past zero, each at sMOTA 1 when kept, 0 when not.
    EXPECT_EQ(c.curve.size(), 6u);
    EXPECT_NEAR(c.samota, 6.0 / 40.0, 1e-12);
    EXPECT_NEAR(d.samota, 0.0, 1e-12);
    EXPECT_EQ(d.all.tp, 7u);  // the first pass (no threshold) keeps everything in both
    // A score that survives re-averaging (0.5: sums and divisions exact) scores the same both ways.
    for (auto& f : tr) f[0].score = 0.5;
    EXPECT_DOUBLE_EQ(evaluate_kitti({gt}, {tr}, devkit).samota,
                     evaluate_kitti({gt}, {tr}, clean).samota);
}

TEST(KittiEval, EmptySequencesAreValid) {
    const KittiEvalResult r = evaluate_kitti({KittiSequence{}}, {KittiSequence{}}, {});
    EXPECT_EQ(r.all.gt, 0u);
    EXPECT_EQ(r.all.fp, 0u);
    EXPECT_TRUE(r.curve.empty());
}

}  // namespace
}  // namespace makeway::eval

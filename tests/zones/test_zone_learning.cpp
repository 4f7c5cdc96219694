// Learned affordance zones: the coverage model against known answers, the learner on constructed
// sessions (matching, motions in the object's frame, symmetry), and the prior taking over when
// there is little to learn from.
#include <gtest/gtest.h>

#include <cmath>

#include "makeway/common/angles.hpp"
#include "makeway/common/random.hpp"
#include "makeway/costmap/affordance.hpp"
#include "makeway/zones/zone_learning.hpp"

namespace makeway::zones {
namespace {

using costmap::AffordanceParams;
using costmap::zone_coordinate;

ObjectEstimate chair_at(double x, double y, double yaw) {
    ObjectEstimate o;
    o.cls = ObjectClass::kChair;
    o.box_world = {{x, y, 0.45}, {0.5, 0.5, 0.9}, yaw};
    return o;
}

SessionObject seen(int session, const ObjectEstimate& o, int place = 0) {
    return {place, session, o.cls, o.box_world, true};
}

// A point at `forward` and `left` of the chair, in its frame.
Eigen::Vector2d beside(const ObjectEstimate& o, double forward, double left) {
    const double c = std::cos(o.box_world.yaw_rad), s = std::sin(o.box_world.yaw_rad);
    return o.box_world.centre_m.head<2>() +
           Eigen::Vector2d(forward * c - left * s, forward * s + left * c);
}

TEST(LearnedZone, CoverageKnownAnswers) {
    // One motion, none: the footprint itself, smoothed: 1 inside, Phi(0) = 0.5 on the middle of an
    // edge, Phi(0)^2 = 0.25 at a corner, nothing 4 kernels out.
    costmap::ClassZone z;
    z.observations = 1;
    z.motions = {{0.0, 0.0, 0.0, 1.0}};
    const Eigen::Vector2d half(0.25, 0.25);
    EXPECT_NEAR(costmap::learned_coverage(z, 0.02, half, {0.0, 0.0}), 1.0, 1e-9);
    EXPECT_NEAR(costmap::learned_coverage(z, 0.02, half, {0.25, 0.0}), 0.5, 1e-9);
    EXPECT_NEAR(costmap::learned_coverage(z, 0.02, half, {0.25, -0.25}), 0.25, 1e-9);
    EXPECT_EQ(costmap::learned_coverage(z, 0.02, half, {0.25 + 0.081, 0.0}), 0.0);
    // Two motions, weights 3 and 1: a point only the second footprint covers has 1/4.
    z.motions = {{0.0, 0.0, 0.0, 3.0}, {-1.0, 0.0, 0.0, 1.0}};
    EXPECT_NEAR(costmap::learned_coverage(z, 0.02, half, {-1.0, 0.0}), 0.25, 1e-9);
    // A quarter turn of a 1 x 0.2 footprint in place covers (0, 0.4), which no shift does.
    z.motions = {{0.0, 0.0, M_PI_2, 1.0}};
    EXPECT_NEAR(costmap::learned_coverage(z, 0.01, {0.5, 0.1}, {0.0, 0.4}), 1.0, 1e-6);
    EXPECT_NEAR(costmap::learned_coverage(z, 0.01, {0.5, 0.1}, {0.4, 0.0}), 0.0, 1e-6);
}

TEST(LearnedZone, TheCachedRasterAgreesWithTheSumOverMotions) {
    // Random motions and footprints: the costmap's raster lookup against the exact sum.
    Rng rng = make_rng(11, 0);
    costmap::LearnedZones z;
    z.chair = costmap::ClassZone{};
    for (int k = 0; k < 60; ++k) {
        z.chair->motions.push_back({uniform(rng, -0.8, 0.3), uniform(rng, -0.5, 0.5),
                                    uniform(rng, -1.5, 1.5), uniform(rng, 0.1, 3.0)});
    }
    z.chair->observations = 60;
    double worst = 0.0;
    for (int f = 0; f < 4; ++f) {
        const Eigen::Vector2d half(uniform(rng, 0.2, 0.3), uniform(rng, 0.2, 0.3));
        for (int k = 0; k < 400; ++k) {
            const Eigen::Vector2d q(uniform(rng, -1.6, 1.6), uniform(rng, -1.6, 1.6));
            worst =
                std::max(worst, std::abs(z.coverage(ObjectClass::kChair, half, q) -
                                         costmap::learned_coverage(*z.chair, z.kernel_m, half, q)));
        }
    }
    EXPECT_LT(worst, 0.01);
    EXPECT_EQ(z.coverage(ObjectClass::kTable, {0.5, 0.5}, {0.0, 0.0}), 0.0);  // no table zone
    // A copy does not share the cache: changing its zone changes what it answers.
    costmap::LearnedZones copy = z;
    copy.chair->motions = {{-2.0, 0.0, 0.0, 1.0}};
    EXPECT_NEAR(copy.coverage(ObjectClass::kChair, {0.25, 0.25}, {-2.0, 0.0}), 1.0, 1e-3);
    EXPECT_EQ(z.coverage(ObjectClass::kChair, {0.25, 0.25}, {-2.0, 0.0}), 0.0);
}

TEST(ZoneLearning, AChairPulledStraightBackTenTimesGetsAZoneBehindItAndNowhereElse) {
    // Session 0: at its table; sessions 1..10: pulled 0.4 m straight back (each from where it
    // stands at the table), seen in time order. No prior: the data alone.
    const ObjectEstimate home = chair_at(3.0, -1.0, deg_to_rad(35.0));
    std::vector<SessionObject> sessions{seen(0, home)};
    for (int k = 1; k <= 10; ++k) {
        const Eigen::Vector2d p = beside(home, -0.4, 0.0);
        sessions.push_back(seen(k, chair_at(p.x(), p.y(), home.box_world.yaw_rad)));
    }
    ZoneLearnParams params;
    params.both_directions = false;
    params.zone.prior_strength = 0.0;
    const ZoneLearning l = learn_zones(sessions, params);
    ASSERT_TRUE(l.zones.chair.has_value());
    EXPECT_EQ(l.chair.motions, 55u);  // 10 from session 0, 45 between the pulled ones
    EXPECT_NEAR(l.chair.moved_share, 10.0 / 55.0, 1e-9);
    EXPECT_DOUBLE_EQ(l.chair.mean_confidence, 1.0);  // one chair: nothing to confuse it with
    EXPECT_FALSE(l.zones.table.has_value());

    AffordanceParams learned;
    learned.learned = std::make_shared<const costmap::LearnedZones>(l.zones);
    for (double back : {0.3, 0.4, 0.55}) {  // behind the chair's back edge (0.25) up to 0.65
        EXPECT_LE(zone_coordinate(home, learned, beside(home, -back, 0.0)), 1.0) << back;
    }
    EXPECT_GT(zone_coordinate(home, learned, beside(home, -0.75, 0.0)), 1.0);  // beyond the pull
    // In front and to either side, two kernels (10 cm) past the chair's edge: nothing. (Within
    // a kernel of the edge the staying sessions' blurred footprint covers more than 0.1.)
    for (double d : {0.35, 0.4, 0.55}) {
        EXPECT_GT(zone_coordinate(home, learned, beside(home, d, 0.0)), 1.0) << d;
        EXPECT_GT(zone_coordinate(home, learned, beside(home, 0.0, d)), 1.0) << d;
        EXPECT_GT(zone_coordinate(home, learned, beside(home, 0.0, -d)), 1.0) << d;
    }
    EXPECT_EQ(zone_coordinate(home, learned, beside(home, 0.1, 0.1)), 0.0);  // on the chair
    // The hand-drawn ellipse reaches 0.85 m both ways: the learned zone is the half of it used.
    const AffordanceParams hand;
    EXPECT_LE(zone_coordinate(home, hand, beside(home, 0.55, 0.0)), 1.0);
}

TEST(ZoneLearning, BothDirectionsByDefault) {
    // A chair seen pulled out is as likely to be pushed back in: with both directions the same
    // sessions give the zone in front of a pulled-out chair as well.
    const ObjectEstimate home = chair_at(0.0, 0.0, 0.0);
    std::vector<SessionObject> sessions{seen(0, home), seen(1, chair_at(-0.4, 0.0, 0.0))};
    ZoneLearnParams params;
    params.zone.prior_strength = 0.0;
    const ZoneLearning l = learn_zones(sessions, params);
    ASSERT_EQ(l.motions.size(), 2u);
    EXPECT_NEAR(l.motions[0].motion.x_m, -0.4, 1e-12);
    EXPECT_NEAR(l.motions[1].motion.x_m, 0.4, 1e-12);
    EXPECT_DOUBLE_EQ(l.zones.chair->observations, 1.0);  // one match, counted once
}

TEST(ZoneLearning, FewObservationsKeepThePaperShapeNoneGiveItExactly) {
    const ObjectEstimate home = chair_at(1.0, 2.0, 0.3);
    const AffordanceParams hand;
    // No observations: exactly the hand-drawn coordinate (and so the same costs), everywhere.
    costmap::LearnedZones empty;
    empty.chair = costmap::ClassZone{};
    AffordanceParams none;
    none.learned = std::make_shared<const costmap::LearnedZones>(empty);
    Rng rng = make_rng(7, 0);
    for (int k = 0; k < 500; ++k) {
        const Eigen::Vector2d p(uniform(rng, -0.5, 2.5), uniform(rng, 0.5, 3.5));
        const double u = zone_coordinate(home, hand, p);
        if (u <= 1.0) {
            EXPECT_EQ(zone_coordinate(home, none, p), u);
            EXPECT_EQ(costmap::zone_cost(home, none, p), costmap::zone_cost(home, hand, p));
        } else {
            EXPECT_EQ(zone_coordinate(home, none, p), u);
        }
    }
    // One observed pull of 0.8 m against a prior of 10: away from where that chair went the zone
    // stays the paper's; where it went the zone reaches, faintly (1 / 11 of the weight: a cost
    // well under the peak). With 1000 such observations it reaches there at nearly the peak cost
    // and no longer forward.
    const auto pulled = [&](int n) {
        costmap::LearnedZones z;
        z.chair = costmap::ClassZone{static_cast<double>(n), {{-0.8, 0.0, 0.0, 1.0}}};
        AffordanceParams a;
        a.learned = std::make_shared<const costmap::LearnedZones>(z);
        return a;
    };
    const AffordanceParams one = pulled(1), many = pulled(1000);
    const Eigen::Vector2d went = beside(home, -0.8, 0.0);
    int agree = 0, total = 0;
    for (int k = 0; k < 2000; ++k) {
        const Eigen::Vector2d p(uniform(rng, -0.5, 2.5), uniform(rng, 0.5, 3.5));
        if ((p - went).norm() < 0.45) continue;
        agree += (zone_coordinate(home, one, p) <= 1.0) == (zone_coordinate(home, hand, p) <= 1.0);
        ++total;
    }
    EXPECT_GE(agree, 0.97 * total);
    const Eigen::Vector2d far_back = beside(home, -1.0, 0.0);  // outside the paper's ellipse
    EXPECT_GT(zone_coordinate(home, hand, far_back), 1.0);
    EXPECT_LE(zone_coordinate(home, one, far_back), 1.0);
    EXPECT_LE(costmap::zone_cost(home, one, far_back), 100);  // c = 0.08: u = ln c / ln 0.03 = 0.73
    EXPECT_GE(costmap::zone_cost(home, many, far_back), 200);
    EXPECT_GT(zone_coordinate(home, many, beside(home, 0.6, 0.0)), 1.0);
    EXPECT_LE(zone_coordinate(home, hand, beside(home, 0.6, 0.0)), 1.0);
}

TEST(ZoneLearning, ObjectsAreMatchedByPositionAndSizeNotByOrder) {
    // Two chairs 0.6 m apart and a table; session 1 lists them in another order, the first chair
    // moved 0.1 m sideways. Confidence: 1 - 0.1 / 0.5 (the other chair is 0.5 m from where it
    // went).
    const ObjectEstimate a = chair_at(0.0, 0.0, 0.0), b = chair_at(0.6, 0.0, 0.0);
    ObjectEstimate t;
    t.cls = ObjectClass::kTable;
    t.box_world = {{0.3, 1.2, 0.37}, {1.6, 0.8, 0.74}, 0.0};
    const ObjectEstimate a1 = chair_at(0.1, 0.0, 0.0);
    const std::vector<SessionObject> s{seen(0, a), seen(0, b), seen(0, t),
                                       seen(1, t), seen(1, b), seen(1, a1)};
    ZoneLearnParams params;
    params.both_directions = false;
    const ZoneLearning l = learn_zones(s, params);
    ASSERT_EQ(l.motions.size(), 3u);
    double moved = 0.0;
    for (const ObjectMotion& m : l.motions) {
        if (m.cls == ObjectClass::kChair && std::abs(m.motion.x_m) > 1e-9) {
            moved += 1;
            EXPECT_NEAR(m.motion.x_m, 0.1, 1e-12);
            EXPECT_NEAR(m.confidence, 1.0 - 0.1 / 0.5, 1e-12);
        }
    }
    EXPECT_EQ(moved, 1);
    EXPECT_EQ(l.chair.unmatched, 0u);
    EXPECT_EQ(l.table.motions, 1u);
    // A chair of another size is not the same chair, however near.
    ObjectEstimate big = chair_at(0.0, 0.0, 0.0);
    big.box_world.size_m.x() = 1.2;
    const ZoneLearning l2 = learn_zones({seen(0, a), seen(1, big)}, params);
    EXPECT_TRUE(l2.motions.empty());
    EXPECT_EQ(l2.chair.unmatched, 2u);
}

TEST(ZoneLearning, PlacesAreNeverComparedAndUnknownFacingsAreLeftOut) {
    // Two labelled places each with its own frame: a chair at the same coordinates in both is
    // two chairs; a chair whose facing no CAD model fixed teaches nothing about front and back.
    const ObjectEstimate a = chair_at(0.0, 0.0, 0.0);
    std::vector<SessionObject> s{seen(0, a, 0), seen(0, chair_at(0.2, 0.0, 0.0), 1)};
    const ZoneLearning l = learn_zones(s, {});
    EXPECT_TRUE(l.motions.empty());
    EXPECT_FALSE(l.zones.chair.has_value());
    SessionObject pca = seen(1, a);
    pca.facing_known = false;
    const ZoneLearning l2 = learn_zones({seen(0, a), pca}, {});
    EXPECT_TRUE(l2.motions.empty());
    EXPECT_EQ(l2.chair.facing_unknown, 1u);
}

TEST(ZoneLearning, SymmetryHalvesAChairsWeightAcrossItsAxis) {
    ZoneLearnParams params;
    const costmap::ClassZone chair = bin_motions({{0.0, 0.3, 0.2}}, ObjectClass::kChair, params);
    ASSERT_EQ(chair.motions.size(), 2u);
    EXPECT_NEAR(chair.motions[0].dy_m, -0.3, 1e-12);
    EXPECT_NEAR(chair.motions[1].dy_m, 0.3, 1e-12);
    EXPECT_DOUBLE_EQ(chair.motions[0].weight, 0.5);
    EXPECT_NEAR(chair.motions[1].dyaw_rad, deg_to_rad(10.0), 1e-12);  // 0.2 rad = 11.5 deg -> 10
    const costmap::ClassZone table = bin_motions({{0.4, 0.1, 0.0}}, ObjectClass::kTable, params);
    EXPECT_EQ(table.motions.size(), 4u);
    params.symmetric = false;
    EXPECT_EQ(bin_motions({{0.4, 0.1, 0.0}}, ObjectClass::kTable, params).motions.size(), 1u);
}

TEST(ZoneLearning, TracksGiveTheMotionsSeenWithinASession) {
    // A chair tracked at 1 Hz for 20 s, pulled 0.4 m back at t = 8 s; a table that stands. Sampled
    // every 5 s (t = 0, 5, 10, 15): motions 0, -0.4, 0 for the chair, three of nothing for the
    // table.
    std::vector<TrackedObject> seen;
    const ObjectEstimate chair = chair_at(1.0, 1.0, M_PI_2);
    for (int t = 0; t < 20; ++t) {
        const Eigen::Vector2d p = beside(chair, t >= 8 ? -0.4 : 0.0, 0.0);
        seen.push_back({0, 7, static_cast<double>(t), ObjectClass::kChair,
                        chair_at(p.x(), p.y(), M_PI_2).box_world});
        seen.push_back({0,
                        9,
                        static_cast<double>(t),
                        ObjectClass::kTable,
                        {{3.0, 3.0, 0.37}, {1.6, 0.8, 0.74}, 0.0}});
    }
    const std::vector<ObjectMotion> motions = track_motions(seen, 5.0);
    ASSERT_EQ(motions.size(), 6u);
    std::vector<double> chair_dx;
    for (const ObjectMotion& m : motions)
        if (m.cls == ObjectClass::kChair) chair_dx.push_back(m.motion.x_m);
    ASSERT_EQ(chair_dx.size(), 3u);
    EXPECT_NEAR(chair_dx[0], 0.0, 1e-12);
    EXPECT_NEAR(chair_dx[1], -0.4, 1e-12);
    EXPECT_NEAR(chair_dx[2], 0.0, 1e-12);
    // They join the sessions' matches as observations of their own.
    const ZoneLearning l = learn_zones({}, {}, motions);
    EXPECT_EQ(l.chair.motions, 3u);
    EXPECT_EQ(l.chair.tracked, 3u);
    EXPECT_DOUBLE_EQ(l.zones.chair->observations, 3.0);
    EXPECT_NEAR(l.chair.moved_share, 1.0 / 3.0, 1e-12);
}

TEST(ZoneLearning, BadParamsAreRefusedWithEveryProblem) {
    ZoneLearnParams p;
    p.match_gate_m = -1.0;
    p.zone.coverage_threshold = 1.5;
    try {
        learn_zones({}, p);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("match_gate_m"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("coverage_threshold"), std::string::npos);
    }
}

}  // namespace
}  // namespace makeway::zones

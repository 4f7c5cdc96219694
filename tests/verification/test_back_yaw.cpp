#include <gtest/gtest.h>

#include <cmath>

#include "chair_scan.hpp"
#include "makeway/common/angles.hpp"
#include "makeway/verification/back_yaw.hpp"
#include "makeway/verification/verifier.hpp"

namespace makeway::verification {
namespace {

constexpr double kDeg = kPi / 180.0;

// The network's box of a scanned chair, turned by `error` [rad] about its centre.
Detection turned_box(const ChairScan& scan, double error) {
    Detection d;
    d.cls = ObjectClass::kChair;
    d.score = 0.9;
    d.box_sensor = scan.box_sensor;
    d.box_sensor.yaw_rad = wrap_angle(scan.box_sensor.yaw_rad + error);
    return d;
}

// A four-legged chair seen from behind and beside (its back rest toward the sensor): a box off by
// up to 30 deg either way turns back to the chair's yaw within a few degrees.
TEST(BackYaw, TurnsAChairBoxToItsBackRest) {
    const ChairScan scan = scan_chair(sim::FurnitureStyle::kFourLegChair, 4, 0.6, 3);
    const BackYawParams params;
    for (const double error : {-0.5, -0.25, 0.0, 0.15, 0.35, 0.5}) {
        const Detection d = turned_box(scan, error);
        const BackYawResult r =
            yaw_from_back(segment_points(scan.cloud_sensor, d.box_sensor, params.margin_m),
                          d.box_sensor, scan.box_sensor.z_min_m(), params);
        ASSERT_TRUE(r.refined) << error << ": " << r.points << " points, elongation "
                               << r.elongation << ", turn " << r.turn_rad;
        EXPECT_LT(std::abs(angle_diff(r.yaw_rad, scan.truth.yaw_rad)), 4.0 * kDeg) << error;
        EXPECT_GE(r.points, params.min_points);
        EXPECT_GE(r.elongation, params.min_elongation);
    }
}

// The network's yaw stays where the back says nothing it can trust: a turn beyond max_turn_rad
// (the axis is pi-ambiguous, so a box 60 deg off would be turned the wrong way), too few points
// (the box over empty floor), a stool's round seat (no axis), and with the refinement off.
TEST(BackYaw, KeepsTheNetworksYawWhereTheBackSaysNothingTrusted) {
    const ChairScan chair = scan_chair(sim::FurnitureStyle::kFourLegChair, 4, 0.6, 3);
    const BackYawParams params;
    const Detection far_off = turned_box(chair, 1.0);
    BackYawResult r =
        yaw_from_back(segment_points(chair.cloud_sensor, far_off.box_sensor, params.margin_m),
                      far_off.box_sensor, chair.box_sensor.z_min_m(), params);
    EXPECT_FALSE(r.refined);
    EXPECT_EQ(r.yaw_rad, far_off.box_sensor.yaw_rad);
    EXPECT_GT(std::abs(r.turn_rad), params.max_turn_rad);  // measured, not trusted

    Detection empty = turned_box(chair, 0.2);
    empty.box_sensor.centre_m.y() -= 2.0;  // beside the chair: floor only (dropped)
    r = yaw_from_back(segment_points(chair.cloud_sensor, empty.box_sensor, params.margin_m),
                      empty.box_sensor, chair.box_sensor.z_min_m(), params);
    EXPECT_FALSE(r.refined);
    EXPECT_LT(r.points, params.min_points);
    EXPECT_EQ(r.yaw_rad, empty.box_sensor.yaw_rad);

    const ChairScan stool = scan_chair(sim::FurnitureStyle::kStool, 2, 0.6, 3);
    const Detection seat = turned_box(stool, 0.2);
    r = yaw_from_back(segment_points(stool.cloud_sensor, seat.box_sensor, params.margin_m),
                      seat.box_sensor, stool.box_sensor.z_min_m(), params);
    EXPECT_FALSE(r.refined) << r.points << " points, elongation " << r.elongation;
    EXPECT_LT(r.elongation, params.min_elongation);

    BackYawParams off;
    off.enabled = false;
    const Detection near = turned_box(chair, 0.2);
    r = yaw_from_back(segment_points(chair.cloud_sensor, near.box_sensor, params.margin_m),
                      near.box_sensor, chair.box_sensor.z_min_m(), off);
    EXPECT_FALSE(r.refined);
    EXPECT_EQ(r.yaw_rad, near.box_sensor.yaw_rad);
}

// Over a keyframe's detections: chairs turned, tables and everything else as the network gave.
TEST(BackYaw, TurnsChairsOnlyAndKeepsTheRest) {
    const ChairScan scan = scan_chair(sim::FurnitureStyle::kOfficeChair, 5, -0.4, 2);
    Detection chair = turned_box(scan, 0.3);
    Detection table = chair;
    table.cls = ObjectClass::kTable;
    const std::vector<Detection> out = chairs_turned_to_their_backs(
        scan.cloud_sensor, {chair, table},
        [&](double, double) { return scan.box_sensor.z_min_m(); }, BackYawParams{});
    ASSERT_EQ(out.size(), 2u);
    EXPECT_LT(std::abs(angle_diff(out[0].box_sensor.yaw_rad, scan.truth.yaw_rad)), 5.0 * kDeg);
    EXPECT_EQ(out[0].score, chair.score);
    EXPECT_TRUE(out[0].box_sensor.centre_m.isApprox(chair.box_sensor.centre_m, 0.0));
    EXPECT_EQ(out[1].box_sensor.yaw_rad, table.box_sensor.yaw_rad);
    // Bad parameters are named.
    BackYawParams bad;
    bad.top_share = 0.0;
    bad.max_turn_rad = 2.0;
    EXPECT_EQ(bad.validate().size(), 2u);
}

}  // namespace
}  // namespace makeway::verification

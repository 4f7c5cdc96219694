// Verification against a learned shape prior's completed mesh, for detections no CAD model fits
// (the supplementary's shape networks stand behind ShapePrior; a fixed answer stands in here).
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

#include "chair_scan.hpp"
#include "makeway/common/angles.hpp"
#include "makeway/sim/furniture.hpp"
#include "makeway/verification/verifier.hpp"

namespace makeway::verification {
namespace {

// A stand-in for the learned prior: it "completes" the segment into a given mesh at a given pose
// (here the chair's true shape, its pose off by 20 deg and 10 cm), or finds nothing.
class FixedPrior : public ShapePrior {
  public:
    FixedPrior(std::optional<Estimate> answer) : answer_(std::move(answer)) {}
    std::optional<Estimate> estimate(const std::vector<Eigen::Vector3d>& segment, ObjectClass,
                                     double floor_z_m) const override {
        ++calls;
        seen_points = segment.size();
        seen_floor = floor_z_m;
        return answer_;
    }
    mutable int calls = 0;
    mutable std::size_t seen_points = 0;
    mutable double seen_floor = 0.0;

  private:
    std::optional<Estimate> answer_;
};

TEST(Verification, AShapePriorVerifiesWhatNoCadModelFits) {
    const ChairScan scan = scan_chair(sim::FurnitureStyle::kOfficeChair, 9, 0.4, 2);
    Detection det;
    det.cls = ObjectClass::kChair;
    det.box_sensor = scan.box_sensor;
    det.box_sensor.yaw_rad += deg_to_rad(70);  // a poor detector yaw
    ShapePrior::Estimate e;
    e.mesh_object = sim::make_furniture(sim::FurnitureStyle::kOfficeChair, 9).mesh_object;
    e.T_sensor_object = make_T_xyz_yaw(scan.truth.t_m + Eigen::Vector3d(0.1, -0.05, 0.0),
                                       scan.truth.yaw_rad + deg_to_rad(20));
    const FixedPrior prior(e);

    // No CAD models at all: without the prior nothing is verified; with it, ICP against the
    // completed shape refines the prior's pose to the truth.
    const CadLibrary empty;
    const VerifiedDetection none = verify_detection(scan.cloud_sensor, det, empty, {}, -0.45);
    EXPECT_FALSE(none.accepted);
    const VerifiedDetection v = verify_detection(scan.cloud_sensor, det, empty, {}, -0.45, &prior);
    ASSERT_TRUE(v.accepted) << v.reason;
    EXPECT_EQ(v.model, "completed shape");
    EXPECT_EQ(prior.calls, 1);
    EXPECT_EQ(prior.seen_points, v.segment_points);
    EXPECT_DOUBLE_EQ(prior.seen_floor, -0.45);
    EXPECT_LT(std::abs(rad_to_deg(angle_diff(yaw_of(v.T_sensor_object), scan.truth.yaw_rad))), 3.0);
    EXPECT_LT((v.T_sensor_object.translation() - scan.truth.t_m).norm(), 0.03);
    EXPECT_EQ(v.detection.box_sensor.yaw_rad, det.box_sensor.yaw_rad);  // the detection as given

    // A CAD model that fits is used and the prior never asked; one that does not fit (a table's)
    // hands over to the prior.
    const CadLibrary right = library_with(sim::FurnitureStyle::kOfficeChair, 9);
    const FixedPrior unused(e);
    EXPECT_EQ(verify_detection(scan.cloud_sensor, det, right, {}, -0.45, &unused).model,
              "office_chair");
    EXPECT_EQ(unused.calls, 0);
    CadLibrary wrong;
    wrong.add("four_leg_chair", ObjectClass::kChair,
              sim::make_furniture(sim::FurnitureStyle::kFourLegChair, 1).mesh_object);
    const VerifiedDetection handed =
        verify_detection(scan.cloud_sensor, det, wrong, {}, -0.45, &prior);
    EXPECT_TRUE(handed.accepted);

    // A prior that finds nothing leaves the detection rejected, and says so.
    const FixedPrior nothing(std::nullopt);
    const VerifiedDetection r =
        verify_detection(scan.cloud_sensor, det, empty, {}, -0.45, &nothing);
    EXPECT_FALSE(r.accepted);
    EXPECT_NE(r.reason.find("shape prior"), std::string::npos) << r.reason;
}

}  // namespace
}  // namespace makeway::verification

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "makeway/perception/levelling.hpp"

namespace makeway::perception {
namespace {

// A sensor 0.9 m above the floor, pitched 12 deg nose-down (about its y axis): in the levelled
// frame every floor point lies at -0.45 m, the up direction is +z, and the heading is kept (the
// sensor's x axis still points along +x, seen from above).
TEST(Levelling, FloorLandsAtTheTrainingHeightHeadingKept) {
    const double pitch = 12.0 * M_PI / 180.0, height = 0.9;
    // T_floor_sensor: the floor frame is level, z up; the sensor sits `height` above its origin.
    Isometry3 T_floor_sensor = Isometry3::Identity();
    T_floor_sensor.linear() = Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()).toRotationMatrix();
    T_floor_sensor.translation() = Eigen::Vector3d(0, 0, height);
    // The floor plane z = 0 in the sensor frame: n = R^T e_z, d = height.
    const Eigen::Vector3d n = T_floor_sensor.linear().transpose() * Eigen::Vector3d::UnitZ();
    const Isometry3 T = level_frame(Eigen::Vector4d(n.x(), n.y(), n.z(), height), 0.45);
    for (const Eigen::Vector3d& floor_point :
         {Eigen::Vector3d(2, 0, 0), Eigen::Vector3d(-1, 3, 0), Eigen::Vector3d(5, -4, 0)}) {
        const Eigen::Vector3d in_sensor = T_floor_sensor.inverse() * floor_point;
        EXPECT_NEAR((T * in_sensor).z(), -0.45, 1e-9);
    }
    EXPECT_TRUE((T.linear() * n).isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
    const Eigen::Vector3d x = T.linear() * Eigen::Vector3d::UnitX();
    EXPECT_NEAR(std::atan2(x.y(), x.x()), 0.0, 1e-12);
    // The real sensor sits right above the virtual one, 0.9 - 0.45 m higher.
    EXPECT_NEAR((T * Eigen::Vector3d::Zero()).head<2>().norm(), 0.0, 1e-12);
    EXPECT_NEAR((T * Eigen::Vector3d::Zero()).z(), height - 0.45, 1e-12);
}

TEST(Levelling, UnusablePlanesAndModelsWithoutAHeightLeaveTheCloudAlone) {
    for (const Eigen::Vector4d& bad :
         {Eigen::Vector4d(0, 0, 1, -0.4), Eigen::Vector4d(0, 0, 2, 0.4),
          Eigen::Vector4d(0, 0, 1, 40.0), Eigen::Vector4d(0, 0, NAN, 0.4)}) {
        EXPECT_TRUE(level_frame(bad, 0.45).isApprox(Isometry3::Identity())) << bad.transpose();
    }
    EXPECT_FALSE(level_frame_if(std::nullopt, 0.45).has_value());
    EXPECT_FALSE(level_frame_if(Eigen::Vector4d(0, 0, 1, 0.7), 0.0).has_value());
    const auto T = level_frame_if(Eigen::Vector4d(0, 0, 1, 0.7), 0.45);
    ASSERT_TRUE(T.has_value());
    EXPECT_NEAR(T->translation().z(), 0.25, 1e-12);  // a sensor 0.7 m up, seen from 0.45 m
}

}  // namespace
}  // namespace makeway::perception

#include <gtest/gtest.h>

#include <cmath>

#include "makeway/perception/training_augment.hpp"

namespace makeway::perception {
namespace {

// Points on the footprint corners and the top centre of a box.
void add_box_points(PointCloud& cloud, const OrientedBox& b) {
    const double c = std::cos(b.yaw_rad), s = std::sin(b.yaw_rad);
    for (double u : {-0.5, 0.5}) {
        for (double v : {-0.5, 0.5}) {
            const double x = u * b.size_m.x(), y = v * b.size_m.y();
            cloud.xyz.emplace_back(static_cast<float>(b.centre_m.x() + c * x - s * y), static_cast<float>(b.centre_m.y() + s * x + c * y),
                                   static_cast<float>(b.centre_m.z()));
        }
    }
}

TEST(TrainingAugment, SameSeedSameSample) {
    PointCloud a;
    add_box_points(a, {{3.0, 1.0, 0.0}, {0.5, 0.45, 0.9}, 0.7});
    for (int i = 0; i < 200; ++i) a.xyz.emplace_back(0.05f * static_cast<float>(i), 1.0f, 0.2f);
    PointCloud b = a;
    LabelledBoxes ba{{ObjectClass::kChair, {{3.0, 1.0, 0.0}, {0.5, 0.45, 0.9}, 0.7}}}, bb = ba;
    Rng ra = make_rng(5), rb = make_rng(5);
    augment_sample(a, ba, ra);
    augment_sample(b, bb, rb);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_LT(a.size(), 205u);  // subsampled
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a.xyz[i], b.xyz[i]);
    ASSERT_EQ(ba.size(), bb.size());
}

}  // namespace
}  // namespace makeway::perception

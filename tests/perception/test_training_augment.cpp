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
            cloud.xyz.emplace_back(static_cast<float>(b.centre_m.x() + c * x - s * y),
                                   static_cast<float>(b.centre_m.y() + s * x + c * y),
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

// Boxes move with their points: every point sampled inside a box (tagged by its intensity) is still
// inside that box after rotation, mirror, subsampling and range dropout, over many seeds.
TEST(TrainingAugment, BoxesMoveWithTheirPoints) {
    Rng sample_rng = make_rng(11);
    LabelledBoxes original;
    PointCloud cloud;
    for (int j = 0; j < 6; ++j) {
        const OrientedBox b{{uniform(sample_rng, -6, 6), uniform(sample_rng, -6, 6), 0.0},
                            {uniform(sample_rng, 0.4, 1.6), uniform(sample_rng, 0.4, 0.9), 0.8},
                            uniform(sample_rng, -3.1, 3.1)};
        original.emplace_back(j % 2 ? ObjectClass::kTable : ObjectClass::kChair, b);
        for (int i = 0; i < 100; ++i) {
            const Eigen::Vector3d local(uniform(sample_rng, -0.45, 0.45) * b.size_m.x(),
                                        uniform(sample_rng, -0.45, 0.45) * b.size_m.y(),
                                        uniform(sample_rng, -0.45, 0.45) * b.size_m.z());
            cloud.xyz.push_back((b.T_frame_box() * local).cast<float>());
            cloud.intensity.push_back(static_cast<float>(j));
        }
    }
    int checked = 0;
    for (std::uint64_t seed = 0; seed < 40; ++seed) {
        PointCloud c = cloud;
        LabelledBoxes boxes = original;
        Rng rng = make_rng(seed);
        augment_sample(c, boxes, rng);
        // Surviving boxes keep their order; find each by its size (unchanged by rigid moves).
        for (const auto& [cls, box] : boxes) {
            int j = -1;
            for (std::size_t k = 0; k < original.size(); ++k) {
                if ((original[k].second.size_m - box.size_m).norm() < 1e-9) j = static_cast<int>(k);
            }
            ASSERT_GE(j, 0) << "seed " << seed << ": a box changed size";
            EXPECT_EQ(cls, original[static_cast<std::size_t>(j)].first);
            const Isometry3 T_box_frame = box.T_frame_box().inverse();
            for (std::size_t i = 0; i < c.size(); ++i) {
                if (c.intensity[i] != static_cast<float>(j)) continue;
                const Eigen::Vector3d q = T_box_frame * c.xyz[i].cast<double>();
                EXPECT_LE(std::abs(q.x()), 0.5 * box.size_m.x() + 1e-4)
                    << "seed " << seed << " box " << j;
                EXPECT_LE(std::abs(q.y()), 0.5 * box.size_m.y() + 1e-4)
                    << "seed " << seed << " box " << j;
                EXPECT_LE(std::abs(q.z()), 0.5 * box.size_m.z() + 1e-4)
                    << "seed " << seed << " box " << j;
                ++checked;
            }
        }
    }
    EXPECT_GT(checked, 5000);
}

}  // namespace
}  // namespace makeway::perception

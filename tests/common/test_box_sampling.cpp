#include <gtest/gtest.h>

#include "makeway/common/box_overlap.hpp"
#include "makeway/common/box_sampling.hpp"

namespace makeway {
namespace {

TEST(BoxSampling, PointsLieOnTheirBoxAndCarryLabels) {
    const LabelledBox lb{{{1, 2, 0.4}, {1.0, 0.5, 0.8}, 0.6}, SemanticLabel::kTable, 7};
    Rng rng = make_rng(3);
    const PointCloud c = sample_box_surfaces({lb}, {.points_per_m2 = 500, .noise_m = 0.0}, rng);
    // Top + 4 sides: 0.5 + 2 * 0.8 + 2 * 0.4 = 2.9 m^2.
    EXPECT_EQ(c.size(), 250u + 2 * 400u + 2 * 200u);
    for (std::size_t i = 0; i < c.size(); ++i) {
        EXPECT_TRUE(lb.box.contains(c.xyz[i].cast<double>(), 1e-5));
        EXPECT_FALSE(lb.box.contains(c.xyz[i].cast<double>(), -1e-3));  // on the surface
        EXPECT_EQ(c.label[i], static_cast<std::uint8_t>(SemanticLabel::kTable));
        EXPECT_EQ(c.instance[i], 7u);
    }
}

TEST(BoxSampling, LayoutIsSeededAndFreeOfOverlaps) {
    ObjectLayoutParams p;
    p.num_objects = 15;
    const auto a = random_object_layout(p);
    const auto b = random_object_layout(p);
    ASSERT_EQ(a.size(), 15u);
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].box.centre_m, b[i].box.centre_m);
        for (std::size_t j = i + 1; j < a.size(); ++j) EXPECT_EQ(iou_bev(a[i].box, a[j].box), 0.0);
        EXPECT_LE(a[i].box.centre_m.head<2>().cwiseAbs().maxCoeff(), 0.5 * p.room_size_m);
    }
    p.seed = 1;
    EXPECT_NE(random_object_layout(p)[0].box.centre_m, a[0].box.centre_m);
}

TEST(BoxSampling, ValidationListsEveryProblem) {
    ObjectLayoutParams p;
    EXPECT_TRUE(p.validate().empty());
    p.num_objects = 0;
    p.table_share = 2.0;
    EXPECT_EQ(p.validate().size(), 2u);
    EXPECT_EQ(validate(BoxSamplingParams{.points_per_m2 = -1, .noise_m = 0.01}).size(), 1u);
}

}  // namespace
}  // namespace makeway

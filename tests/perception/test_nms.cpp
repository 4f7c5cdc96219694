#include <gtest/gtest.h>

#include "makeway/perception/nms.hpp"

namespace makeway::perception {
namespace {

Detection det(double x, double y, double score, ObjectClass cls = ObjectClass::kChair,
              double yaw = 0.0) {
    Detection d;
    d.box_sensor = {{x, y, 0.0}, {0.5, 0.5, 0.9}, yaw};
    d.score = score;
    d.cls = cls;
    return d;
}

TEST(RotatedNms, KeepsTheBestOfOverlappingBoxesAndEveryLoneOne) {
    // Boxes 0.1 m apart overlap by IoU 0.67; a rotated copy at the same place overlaps 0.83.
    const auto kept = rotated_nms({det(0, 0, 0.6), det(0.1, 0, 0.9),
                                   det(0.05, 0, 0.7, ObjectClass::kChair, 0.4), det(3, 0, 0.3)});
    ASSERT_EQ(kept.size(), 2u);
    EXPECT_DOUBLE_EQ(kept[0].score, 0.9);
    EXPECT_DOUBLE_EQ(kept[1].score, 0.3);
    // Boxes touching at IoU below the threshold both stay.
    EXPECT_EQ(rotated_nms({det(0, 0, 0.9), det(0.45, 0, 0.8)}).size(), 2u);
    // Per class: a table on top of a chair survives only when classes are kept apart.
    EXPECT_EQ(rotated_nms({det(0, 0, 0.9), det(0, 0, 0.8, ObjectClass::kTable)}).size(), 1u);
    EXPECT_EQ(
        rotated_nms({det(0, 0, 0.9), det(0, 0, 0.8, ObjectClass::kTable)}, {.per_class = true})
            .size(),
        2u);
    EXPECT_TRUE(rotated_nms({}).empty());
    EXPECT_EQ(
        rotated_nms({det(0, 0, 0.1), det(2, 0, 0.2), det(4, 0, 0.3)}, {.max_detections = 2}).size(),
        2u);
}

}  // namespace
}  // namespace makeway::perception

#include <gtest/gtest.h>

#include <cmath>

#include "makeway/perception/bev_grid.hpp"

namespace makeway::perception {
namespace {

TEST(BevGrid, PointsLandInTheirCellAndSlice) {
    BevGridParams g;  // 8 m, 0.1 m cells, 9 slices over [-0.5, 1.3) m
    g.intensity = true;
    PointCloud c;
    c.xyz = {
        {1.05f, -2.05f, 0.0f}, {1.05f, -2.05f, 0.05f}, {20.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 5.0f}};
    c.intensity = {0.4f, 0.6f, 1.0f, 1.0f};
    const std::vector<float> bev = encode_bev(c, g);
    ASSERT_EQ(bev.size(), static_cast<std::size_t>(g.channels() * g.cells() * g.cells()));
    const int n = g.cells(), ix = 90, iy = 59;  // floor((1.05 + 8) / 0.1), floor((-2.05 + 8) / 0.1)
    const auto at = [&](int ch) { return bev[static_cast<std::size_t>((ch * n + iy) * n + ix)]; };
    EXPECT_FLOAT_EQ(at(2), std::log1p(2.0f));  // both in slice floor(0.5 / 0.2) = 2
    EXPECT_NEAR(at(g.height_slices), (0.05 + 0.5) / 1.8, 1e-6);  // top height, normalised
    EXPECT_NEAR(at(g.height_slices + 1), 0.5, 1e-6);             // mean intensity
    double total = 0;
    for (int ch = 0; ch < g.height_slices; ++ch) {
        for (int k = 0; k < n * n; ++k) total += bev[static_cast<std::size_t>(ch * n * n + k)];
    }
    EXPECT_FLOAT_EQ(static_cast<float>(total), std::log1p(2.0f));  // out-of-range points dropped
    // The default grid is geometry only: no intensity channel, and intensity changes nothing.
    const BevGridParams geometry;
    EXPECT_EQ(geometry.channels(), geometry.height_slices + 1);
    PointCloud brighter = c;
    for (float& i : brighter.intensity) i *= 100.0f;
    EXPECT_EQ(encode_bev(c, geometry), encode_bev(brighter, geometry));
}

TEST(BevGrid, DecodesPeaksIntoBoxesAndSuppressesDuplicates) {
    const BevGridParams g;
    const int n = g.out_cells();
    std::vector<float> heads(static_cast<std::size_t>(kHeadChannels * n * n), 0.0f);
    auto set = [&](int ch, int iy, int ix, float v) {
        heads[static_cast<std::size_t>((ch * n + iy) * n + ix)] = v;
    };
    auto box = [&](int iy, int ix, double yaw) {
        const int b = kNumObjectClasses;
        set(b, iy, ix, 0.5f), set(b + 1, iy, ix, 0.25f), set(b + 2, iy, ix, 0.1f);
        set(b + 3, iy, ix, std::log(0.5f)), set(b + 4, iy, ix, std::log(0.4f)),
            set(b + 5, iy, ix, std::log(0.9f));
        set(b + 6, iy, ix, static_cast<float>(std::sin(yaw))),
            set(b + 7, iy, ix, static_cast<float>(std::cos(yaw)));
    };
    set(0, 20, 10, 0.8f), set(1, 20, 10, 0.2f), box(20, 10, 0.3);  // a chair
    set(0, 20, 11, 0.6f);                                          // its shoulder: not a peak
    set(0, 22, 10, 0.7f), box(22, 10, 0.3);      // a second peak whose box lands on the first
    set(kNumObjectClasses + 1, 22, 10, -1.75f);  // (offset back by 2 cells): NMS drops it
    set(1, 60, 60, 0.9f), set(0, 60, 60, 0.1f), box(60, 60, -1.0);  // a table far away
    set(0, 70, 70, 0.2f);                                           // below the threshold
    const auto dets = decode_heads(heads, g, {});
    ASSERT_EQ(dets.size(), 2u);
    EXPECT_EQ(dets[0].cls, ObjectClass::kTable);
    EXPECT_FLOAT_EQ(static_cast<float>(dets[0].score), 0.9f);
    const Detection& chair = dets[1];
    EXPECT_EQ(chair.cls, ObjectClass::kChair);
    EXPECT_NEAR(chair.box_sensor.centre_m.x(), (10 + 0.5) * 0.2 - 8.0, 1e-6);
    EXPECT_NEAR(chair.box_sensor.centre_m.y(), (20 + 0.25) * 0.2 - 8.0, 1e-6);
    EXPECT_NEAR(chair.box_sensor.centre_m.z(), 0.1, 1e-6);
    EXPECT_NEAR(chair.box_sensor.size_m.x(), 0.5, 1e-6);
    EXPECT_NEAR(chair.box_sensor.yaw_rad, 0.3, 1e-6);
    EXPECT_NEAR(chair.class_probabilities[0], 0.8, 1e-6);
    EXPECT_TRUE(decode_heads({}, g, {}).empty());  // wrong size: nothing

    // Garbage in the heads (an absurd input drove the network there) is never a detection: a box
    // of e^20 m, one of e^-20 m, a NaN centre, a NaN score.
    std::vector<float> bad(heads.size(), 0.0f);
    auto put = [&](int ch, int iy, int ix, float v) {
        bad[static_cast<std::size_t>((ch * n + iy) * n + ix)] = v;
    };
    const int b = kNumObjectClasses;
    for (int k = 0; k < 4; ++k) {
        const int ix = 10 + 10 * k;
        put(0, 30, ix, 0.95f);
        for (int c = 3; c < 6; ++c) put(b + c, 30, ix, std::log(0.5f));
        put(b + 7, 30, ix, 1.0f);
    }
    for (int c = 3; c < 6; ++c) put(b + c, 30, 10, 20.0f);
    for (int c = 3; c < 6; ++c) put(b + c, 30, 20, -20.0f);
    put(b, 30, 30, std::nanf(""));
    put(0, 30, 40, std::nanf(""));
    EXPECT_TRUE(decode_heads(bad, g, {}).empty());
    put(b + 3, 30, 10, std::log(0.5f)), put(b + 4, 30, 10, std::log(0.5f)),
        put(b + 5, 30, 10, std::log(0.5f));
    EXPECT_EQ(decode_heads(bad, g, {}).size(), 1u);  // the sane one of them
}

}  // namespace
}  // namespace makeway::perception

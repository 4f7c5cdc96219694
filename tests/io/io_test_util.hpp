#pragma once
// Shared by the io tests: seeded clouds with extreme values, bitwise comparison, temp folders.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <limits>
#include <string>

#include "makeway/common/point_cloud.hpp"
#include "makeway/common/random.hpp"

namespace makeway::testing_util {

/// A folder under the test temp dir, fresh for each test (or, from SetUpTestSuite, for the suite).
inline std::filesystem::path fresh_dir(const std::string& name) {
    const ::testing::UnitTest& unit = *::testing::UnitTest::GetInstance();
    const auto* info = unit.current_test_info();
    const std::string owner =
        info
            ? std::string(info->test_suite_name()) + "." + info->name()
            : std::string(unit.current_test_suite() ? unit.current_test_suite()->name() : "suite") +
                  ".suite";
    const auto dir =
        std::filesystem::path(::testing::TempDir()) / "makeway_tests" / (owner + "." + name);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

/// Random values in every channel, plus values that break sloppy codecs: -0, denormals, the
/// largest floats, integer limits.
inline PointCloud random_cloud(std::uint64_t seed, std::size_t n, PointFields fields) {
    Rng rng = make_rng(seed);
    PointCloud c;
    c.resize(n, fields);
    for (std::size_t i = 0; i < n; ++i) {
        for (int k = 0; k < 3; ++k) c.xyz[i][k] = static_cast<float>(normal(rng, 0.0, 30.0));
        if (fields.intensity) c.intensity[i] = static_cast<float>(uniform(rng, 0, 255));
        if (fields.ring) c.ring[i] = static_cast<std::uint16_t>(uniform_int(rng, 0, 65535));
        if (fields.time) c.time_s[i] = static_cast<float>(uniform(rng, 0, 0.1));
        if (fields.label) c.label[i] = static_cast<std::uint8_t>(uniform_int(rng, 0, 255));
        if (fields.instance)
            c.instance[i] = static_cast<std::uint32_t>(uniform_int(rng, 0, 4294967295));
    }
    if (n >= 4) {
        c.xyz[0] = {-0.0f, std::numeric_limits<float>::denorm_min(),
                    std::numeric_limits<float>::max()};
        c.xyz[1] = {std::numeric_limits<float>::lowest(), std::numeric_limits<float>::min(),
                    1e-30f};
        if (fields.ring) c.ring[2] = 65535;
        if (fields.instance) c.instance[3] = 4294967295u;
        if (fields.time) c.time_s[1] = 1.0f / 3.0f;
    }
    return c;
}

template <typename T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

inline ::testing::AssertionResult clouds_bit_equal(const PointCloud& a, const PointCloud& b) {
    if (a.size() != b.size())
        return ::testing::AssertionFailure() << "sizes " << a.size() << " vs " << b.size();
    if (!same_bits(a.xyz, b.xyz)) return ::testing::AssertionFailure() << "xyz differ";
    if (!same_bits(a.intensity, b.intensity))
        return ::testing::AssertionFailure() << "intensity differs";
    if (!same_bits(a.ring, b.ring)) return ::testing::AssertionFailure() << "ring differs";
    if (!same_bits(a.time_s, b.time_s)) return ::testing::AssertionFailure() << "time differs";
    if (!same_bits(a.label, b.label)) return ::testing::AssertionFailure() << "label differs";
    if (!same_bits(a.instance, b.instance))
        return ::testing::AssertionFailure() << "instance differs";
    return ::testing::AssertionSuccess();
}

}  // namespace makeway::testing_util

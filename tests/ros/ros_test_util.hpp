#pragma once
// What the ROS message and bag tests share: PointCloud2 fields and values written by hand, a fresh
// temporary folder, a small cloud with every field.
#include <sensor_msgs/PointCloud2.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>

#include "makeway/common/point_cloud.hpp"

namespace makeway::rosio::test {

using sensor_msgs::PointField;

inline PointField field(const std::string& name, std::uint32_t offset, std::uint8_t type) {
    PointField f;
    f.name = name;
    f.offset = offset;
    f.datatype = type;
    f.count = 1;
    return f;
}

template <typename T>
void put(sensor_msgs::PointCloud2& m, std::size_t point, std::uint32_t offset, T v) {
    std::memcpy(m.data.data() + point * m.point_step + offset, &v, sizeof(T));
}

inline std::filesystem::path fresh_dir(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() / ("makeway_test_ros_" + name);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

inline PointCloud sample_cloud() {
    PointCloud c;
    PointFields f;
    f.intensity = f.ring = f.time = true;
    c.resize(3, f);
    c.xyz = {{1.0f, 2.0f, 0.5f}, {-3.25f, 0.125f, 1.5f}, {10.0f, -4.0f, -0.25f}};
    c.intensity = {10.0f, 55.5f, 200.0f};
    c.ring = {0, 17, 31};
    c.time_s = {0.0f, 0.05f, 0.0999f};
    return c;
}

}  // namespace makeway::rosio::test

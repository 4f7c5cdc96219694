#include "io/kitti_bin.hpp"

#include <cstring>

#include "io/error.hpp"

namespace makeway::io {

CloudFile parse_kitti_bin(std::string_view bytes) {
    constexpr std::size_t kStride = 4 * sizeof(float);
    if (bytes.size() % kStride != 0) {
        throw FormatError("size " + std::to_string(bytes.size()) +
                          " bytes is not a multiple of 16 (float32 x y z intensity per point)");
    }
    CloudFile out;
    out.info = {"kitti_bin", "binary", {"x", "y", "z", "intensity"}, {}};
    const std::size_t n = bytes.size() / kStride;
    out.cloud.resize(n, PointFields{.intensity = true});
    for (std::size_t i = 0; i < n; ++i) {
        const char* p = bytes.data() + i * kStride;
        std::memcpy(out.cloud.xyz[i].data(), p, 3 * sizeof(float));
        std::memcpy(&out.cloud.intensity[i], p + 3 * sizeof(float), sizeof(float));
    }
    return out;
}

std::string serialize_kitti_bin(const PointCloud& cloud) {
    std::string out(cloud.size() * 4 * sizeof(float), '\0');
    char* dst = out.data();
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const float intensity = cloud.intensity.empty() ? 0.0f : cloud.intensity[i];
        std::memcpy(dst, cloud.xyz[i].data(), 3 * sizeof(float));
        std::memcpy(dst + 3 * sizeof(float), &intensity, sizeof(float));
        dst += 4 * sizeof(float);
    }
    return out;
}

}  // namespace makeway::io

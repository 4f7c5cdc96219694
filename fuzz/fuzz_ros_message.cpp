// libFuzzer target: the byte walks of PointCloud2 and Odometry messages must either pass or throw
// FormatError; never read past the bytes (seeded with messages of the simulator's bags).
#include <cstddef>
#include <cstdint>

#include "io/error.hpp"
#include "ros/bag_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        makeway::rosio::check_cloud_message(data, size);
    } catch (const makeway::io::FormatError&) {
    }
    try {
        makeway::rosio::check_odometry_message(data, size);
    } catch (const makeway::io::FormatError&) {
    }
    return 0;
}

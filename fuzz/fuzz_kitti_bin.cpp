// libFuzzer target: parse_kitti_bin must either parse or throw FormatError; never crash, hang or
// leak.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "io/error.hpp"
#include "io/kitti_bin.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try {
        makeway::io::parse_kitti_bin(bytes);
    } catch (const makeway::io::FormatError&) {
    }
    return 0;
}

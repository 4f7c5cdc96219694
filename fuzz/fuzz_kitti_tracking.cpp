// libFuzzer target: parse_kitti_tracking (KITTI tracking labels, detections, DontCare lines) must
// either parse or throw FormatError; never crash, hang or leak.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "io/error.hpp"
#include "io/tracking_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try {
        for (const auto& r : makeway::io::parse_kitti_tracking(bytes)) {
            if (!r.is_dont_care()) (void)makeway::io::box_from_kitti(r);
        }
    } catch (const makeway::io::FormatError&) {
    }
    return 0;
}

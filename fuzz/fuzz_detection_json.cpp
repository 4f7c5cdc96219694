// libFuzzer target: parse_detection_frame (makeway detection JSON, scores as probabilities or
// logits) must either parse or throw FormatError; never crash, hang or leak.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "io/error.hpp"
#include "io/tracking_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    for (bool any_score : {false, true}) {
        try {
            (void)makeway::io::parse_detection_frame(bytes, any_score);
        } catch (const makeway::io::FormatError&) {
        }
    }
    return 0;
}

// libFuzzer target: a frame of objects (tracks or ground truth, what `track` writes and
// `eval-tracking` reads) must either read or throw FileError; never crash, hang or leak.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz/fuzz_util.hpp"
#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/tracking_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto& dir = makeway::fuzz::private_dir();
    try {
        makeway::io::write_file_atomic(dir / "000000.json",
                                       std::string_view(reinterpret_cast<const char*>(data), size));
        makeway::io::read_object_frame(dir / "000000.json");
    } catch (const makeway::io::FileError&) {
    }
    return 0;
}

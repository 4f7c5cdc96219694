// libFuzzer target: parse_scene must either parse or throw FormatError; never crash, hang or leak.
// User meshes are not loaded (no base folder), so the fuzzer never touches the file system.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "io/error.hpp"
#include "io/scene_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try {
        makeway::io::parse_scene(bytes);
    } catch (const makeway::io::FormatError&) {
    }
    return 0;
}

// libFuzzer target: parse_mesh (assimp behind our own checks) must either parse or throw
// FormatError for PLY, OBJ, STL and DAE; never crash, hang or leak. The first byte picks the
// format, the rest is the file. The reader's own time limit (2 s here; 60 s for users) stays below
// libFuzzer's -timeout (10 s): an input assimp is slow on must end as the FormatError users get
// ("the reader took longer than ..."), not as the harness's timeout.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "io/error.hpp"
#include "io/mesh_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    static const char* const kFormats[] = {"ply", "obj", "stl", "dae"};
    const std::string format = kFormats[data[0] % 4];
    const std::string_view bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
    try {
        makeway::io::parse_mesh(bytes, format, {.seconds = 2.0});
    } catch (const makeway::io::FormatError&) {
    }
    return 0;
}

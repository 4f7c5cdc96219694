// libFuzzer target: read_map_server (map_server YAML + PGM image) must either read or throw
// FileError; never crash, hang or leak. The input is the YAML, a NUL byte, then the image; both
// are written to a private folder because the YAML names its image by file name.
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_util.hpp"
#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/map_server_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto [yaml, image] = makeway::fuzz::split_at_nul(data, size);
    const auto& dir = makeway::fuzz::private_dir();
    try {
        makeway::io::write_file_atomic(dir / "map.yaml", yaml);
        makeway::io::write_file_atomic(dir / "map.pgm", image);
        makeway::io::read_map_server(dir / "map.yaml");
    } catch (const makeway::io::FileError&) {
    }
    return 0;
}

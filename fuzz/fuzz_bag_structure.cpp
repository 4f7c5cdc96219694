// libFuzzer target: check_bag_structure must either pass a file or throw FileError; never crash,
// hang or read past the file (seeded with bags rosbag wrote, LZ4 chunks and uncompressed ones).
#include <cstddef>
#include <cstdint>
#include <fstream>

#include "fuzz_util.hpp"
#include "io/error.hpp"
#include "ros/bag_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto path = makeway::fuzz::private_dir() / "in.bag";
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    try {
        makeway::rosio::check_bag_structure(path);
    } catch (const makeway::io::FileError&) {
    }
    return 0;
}

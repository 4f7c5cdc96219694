// libFuzzer target: a detector dataset folder (labels/000000.json + clouds/000000.bin, what
// `makeway dataset` writes and train-detector reads) must either read or throw FileError; never
// crash, hang or leak. The input is the label JSON, a NUL byte, then the KITTI .bin cloud.
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_util.hpp"
#include "io/dataset_io.hpp"
#include "io/error.hpp"
#include "io/file_util.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto [label, cloud] = makeway::fuzz::split_at_nul(data, size);
    const auto& dir = makeway::fuzz::private_dir();
    try {
        makeway::io::write_file_atomic(dir / "labels" / "000000.json", label);
        makeway::io::write_file_atomic(dir / "clouds" / "000000.bin", cloud);
        makeway::io::read_detection_dataset(dir);
    } catch (const makeway::io::FileError&) {
    }
    return 0;
}

// libFuzzer target: the model-file container check (libzip) that stands in front of libtorch's
// reader must answer for any bytes; never crash, hang or leak. torch itself is exercised by the
// mutation test in tests/perception (the clang fuzz build has no libtorch).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "makeway/perception/model_archive.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    (void)makeway::perception::model_archive_problem(
        std::string_view(reinterpret_cast<const char*>(data), size));
    return 0;
}

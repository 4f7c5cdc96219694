#pragma once
// Where the default detector weights are: models/detector.pt in the working directory, else in the
// source tree the program was built in (build/bin/makeway -> ../../models/detector.pt).
#include <filesystem>
#include <optional>
#include <system_error>

namespace makeway::apps {

inline std::optional<std::filesystem::path> default_model_path() {
    namespace fs = std::filesystem;
    const fs::path local = fs::path("models") / "detector.pt";
    if (fs::exists(local)) return local;
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        const fs::path beside = exe.parent_path().parent_path().parent_path() / "models" / "detector.pt";
        if (fs::exists(beside)) return beside;
    }
    return std::nullopt;
}

}  // namespace makeway::apps

#pragma once
// Where the default detector weights are: models/detector.pt in the working directory, else in the
// source tree the program was built in (build/bin/makeway -> ../../models/detector.pt).
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>

#include "io/error.hpp"
#include "makeway/perception/detector.hpp"
#include "makeway/shape/shape_model.hpp"

namespace makeway::apps {

inline std::optional<std::filesystem::path> default_model_path(
    const std::string& name = "detector.pt") {
    namespace fs = std::filesystem;
    const fs::path local = fs::path("models") / name;
    if (fs::exists(local)) return local;
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        const fs::path beside = exe.parent_path().parent_path().parent_path() / "models" / name;
        if (fs::exists(beside)) return beside;
    }
    return std::nullopt;
}

/// A loader's error about the model file itself ("PATH: what") as an io::FileError naming it;
/// anything else (the networks' module could not be opened) as it was thrown. Call it from the
/// handler of `e`.
[[noreturn]] inline void rethrow_model_error(const std::filesystem::path& path,
                                             const std::runtime_error& e) {
    const std::optional<std::string> problem = io::problem_after_path(path.string(), e.what());
    if (!problem) throw;  // called from the handler: the same exception
    throw io::FileError(path.string(), *problem);
}

/// The given model file, else the default weights; throws io::FileError naming the file when it is
/// missing or not a detector.
inline perception::Detector load_detector(const std::string& given) {
    const std::filesystem::path path =
        !given.empty()
            ? std::filesystem::path(given)
            : default_model_path().value_or(std::filesystem::path("models") / "detector.pt");
    try {
        return perception::Detector::load(path);
    } catch (const std::runtime_error& e) {
        rethrow_model_error(path, e);
    }
}

/// load_detector() for the online system (run, navigate, bench nav, demo): the network on one
/// thread. On this 2-core machine a second thread gains the network nothing (detect 7.7-8.1
/// against 7.8-7.9 ms median) while OpenBLAS's second worker spins in sched_yield after every call
/// beside verification's threads: `run --bag` on the dense drive with its CAD models, keyframe
/// chain 65.0-70.3 -> 45.4-52.2 ms median, verification 46.9-53.6 -> 32.7-34.7 ms. bench nav's
/// runs, which go in parallel, and `navigate`'s replay of one of them run the network alike.
inline perception::Detector load_online_detector(const std::string& given) {
    perception::Detector detector = load_detector(given);
    perception::set_inference_threads(1);
    return detector;
}

/// The given shape model file, else models/shape.pt; throws io::FileError naming the file.
inline shape::ShapeModel load_shape_model(const std::string& given) {
    const std::filesystem::path path =
        !given.empty()
            ? std::filesystem::path(given)
            : default_model_path("shape.pt").value_or(std::filesystem::path("models") / "shape.pt");
    try {
        return shape::ShapeModel::load(path);
    } catch (const std::runtime_error& e) {
        rethrow_model_error(path, e);
    }
}

}  // namespace makeway::apps

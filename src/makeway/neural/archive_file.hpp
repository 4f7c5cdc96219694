#pragma once
// Model files, the detector's and the shape networks': written whole or not at all, and one that
// cannot be read named in one line.
#include <torch/torch.h>

#include <filesystem>
#include <string>

#include "makeway/perception/model_archive.hpp"

namespace makeway::perception {

/// Writes `archive` beside `path`, then renames it there: a reader never sees half a model.
inline void save_archive_atomically(torch::serialize::OutputArchive& archive,
                                    const std::filesystem::path& path) {
    const std::filesystem::path tmp = path.string() + ".tmp";
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    archive.save_to(tmp.string());
    std::filesystem::rename(tmp, path);
}

/// Call from the handler (`catch (...)`) around the load of the KIND file at `path`: the exception
/// in hand again as a std::runtime_error "PATH: ..." of one line. A message that names the file
/// already passes as it is; torch's errors, and whatever else its readers throw on a damaged
/// archive (the TorchScript type parser, std::bad_alloc for a size field gone wild), are "not a
/// readable KIND"; anything that is not a std::exception passes untouched.
[[noreturn]] inline void rethrow_load_error(const std::filesystem::path& path,
                                            const std::string& kind) {
    try {
        throw;
    } catch (const c10::Error& e) {
        throw std::runtime_error(path.string() + ": not a readable " + kind + " (" +
                                 first_line(e.what_without_backtrace()) + ")");
    } catch (const std::runtime_error& e) {
        const std::string what = e.what();
        if (what.rfind(path.string(), 0) == 0) throw;
        throw std::runtime_error(path.string() + ": " + first_line(what));
    } catch (const std::exception& e) {
        throw std::runtime_error(path.string() + ": not a readable " + kind + " (" +
                                 first_line(e.what()) + ")");
    }
}

}  // namespace makeway::perception

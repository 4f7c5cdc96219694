#pragma once
// Model files are written whole or not at all (the detector's and the shape networks' save()).
#include <torch/torch.h>

#include <filesystem>

namespace makeway::perception {

/// Writes `archive` beside `path`, then renames it there: a reader never sees half a model.
inline void save_archive_atomically(torch::serialize::OutputArchive& archive,
                                    const std::filesystem::path& path) {
    const std::filesystem::path tmp = path.string() + ".tmp";
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    archive.save_to(tmp.string());
    std::filesystem::rename(tmp, path);
}

}  // namespace makeway::perception

#pragma once
// Whole-file reads and atomic writes (temporary file in the same folder, then rename): a crash or
// an error never leaves a half-written output behind.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

namespace makeway::io {

/// Reads a whole regular file. Throws FileError (missing, a folder, unreadable, larger than
/// max_bytes, or empty when allow_empty is false).
std::string read_file(const std::filesystem::path& path, bool allow_empty = false,
                      std::size_t max_bytes = std::size_t{8} << 30);

/// Writes `data` to `path` atomically. Creates missing parent folders. Throws FileError.
void write_file_atomic(const std::filesystem::path& path, std::string_view data);

/// Lower-case extension without the dot ("pcd"), or "" when there is none.
std::string lower_extension(const std::filesystem::path& path);
/// ASCII lower case (type names, extensions: files from other tools spell them either way).
std::string to_lower(std::string text);

/// A frame's file name stem, zero-padded to six digits ("000042"): recordings, datasets, runs.
std::string frame_name(std::size_t index);

}  // namespace makeway::io

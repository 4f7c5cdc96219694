#pragma once
// Point-cloud files by extension: .pcd, .ply, .bin (KITTI). All writes are atomic.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/cloud_file.hpp"
#include "io/pcd.hpp"
#include "io/ply.hpp"

namespace makeway::io {

enum class CloudFormat { kPcd, kPly, kKittiBin };

/// From the file extension; nullopt for anything else.
std::optional<CloudFormat> cloud_format_from_path(const std::filesystem::path& path);

/// What to do with points whose coordinates are NaN or infinite.
enum class NonFinitePolicy { kReject, kKeep, kDrop };

struct CloudReadOptions {
    NonFinitePolicy non_finite = NonFinitePolicy::kReject;
};

struct CloudWriteOptions {
    PcdEncoding pcd = PcdEncoding::kBinary;
    PlyEncoding ply = PlyEncoding::kBinaryLittleEndian;
};

/// The sweeps of a recording folder: its .pcd, .ply and .bin files, in name order. Throws
/// FileError when `dir` is not a folder or holds none.
std::vector<std::filesystem::path> sweep_files(const std::filesystem::path& dir);

/// Reads any supported file. Throws FileError("PATH: what is wrong") on every kind of bad input.
CloudFile read_point_cloud(const std::filesystem::path& path, const CloudReadOptions& options = {});

/// Parses a buffer in a known format (used by the fuzzers). Throws FormatError.
CloudFile parse_point_cloud(std::string_view bytes, CloudFormat format);

/// Writes atomically; throws FileError. Returns the channels the format cannot hold (dropped).
std::vector<std::string> write_point_cloud(const std::filesystem::path& path,
                                           const PointCloud& cloud,
                                           const CloudWriteOptions& options = {});

std::optional<PcdEncoding> parse_pcd_encoding(std::string_view name);
std::optional<PlyEncoding> parse_ply_encoding(std::string_view name);

}  // namespace makeway::io

#include "io/point_cloud_io.hpp"

#include <algorithm>
#include <system_error>

#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/kitti_bin.hpp"

namespace makeway::io {

std::optional<CloudFormat> cloud_format_from_path(const std::filesystem::path& path) {
    const std::string ext = lower_extension(path);
    if (ext == "pcd") return CloudFormat::kPcd;
    if (ext == "ply") return CloudFormat::kPly;
    if (ext == "bin") return CloudFormat::kKittiBin;
    return std::nullopt;
}

CloudFile parse_point_cloud(std::string_view bytes, CloudFormat format) {
    switch (format) {
        case CloudFormat::kPcd:
            return parse_pcd(bytes);
        case CloudFormat::kPly:
            return parse_ply(bytes);
        case CloudFormat::kKittiBin:
            return parse_kitti_bin(bytes);
    }
    throw FormatError("unknown format");
}

CloudFile read_point_cloud(const std::filesystem::path& path, const CloudReadOptions& options) {
    const auto format = cloud_format_from_path(path);
    if (!format) {
        throw FileError(path.string(),
                        "unknown point-cloud extension (expected .pcd, .ply or .bin)");
    }
    const std::string bytes = read_file(path);
    CloudFile file;
    try {
        file = parse_point_cloud(bytes, *format);
    } catch (const FormatError& e) {
        throw FileError(path.string(), e.what());
    } catch (const std::bad_alloc&) {
        throw FileError(path.string(), "not enough memory for the declared point count");
    }
    const std::size_t bad = file.cloud.count_non_finite();
    if (bad > 0 && options.non_finite == NonFinitePolicy::kReject) {
        std::size_t first = 0;
        while (file.cloud.xyz[first].allFinite()) ++first;
        throw FileError(path.string(), std::to_string(bad) +
                                           " points have NaN or infinite coordinates (first at "
                                           "index " +
                                           std::to_string(first) + ")");
    }
    if (bad > 0 && options.non_finite == NonFinitePolicy::kDrop) {
        file.cloud = remove_non_finite(file.cloud);
    }
    return file;
}

std::vector<std::filesystem::path> sweep_files(const std::filesystem::path& dir) {
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec))
        throw FileError(dir.string(), "not a folder of sweeps");
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
        const std::string ext = lower_extension(e.path());
        if (e.is_regular_file() && (ext == "pcd" || ext == "ply" || ext == "bin"))
            files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    if (files.empty()) throw FileError(dir.string(), "no .pcd, .ply or .bin sweeps");
    return files;
}

std::vector<std::string> write_point_cloud(const std::filesystem::path& path,
                                           const PointCloud& cloud,
                                           const CloudWriteOptions& options) {
    const auto format = cloud_format_from_path(path);
    if (!format) {
        throw FileError(path.string(),
                        "unknown point-cloud extension (expected .pcd, .ply or .bin)");
    }
    if (const std::string err = cloud.consistency_error(); !err.empty()) {
        throw FileError(path.string(), "inconsistent cloud: " + err);
    }
    std::vector<std::string> dropped;
    std::string bytes;
    switch (*format) {
        case CloudFormat::kPcd:
            bytes = serialize_pcd(cloud, options.pcd);
            break;
        case CloudFormat::kPly:
            bytes = serialize_ply(cloud, options.ply);
            break;
        case CloudFormat::kKittiBin: {
            const PointFields f = cloud.fields();
            if (f.ring) dropped.push_back("ring");
            if (f.time) dropped.push_back("time");
            if (f.label) dropped.push_back("label");
            if (f.instance) dropped.push_back("instance");
            bytes = serialize_kitti_bin(cloud);
            break;
        }
    }
    write_file_atomic(path, bytes);
    return dropped;
}

std::optional<PcdEncoding> parse_pcd_encoding(std::string_view name) {
    if (name == "ascii") return PcdEncoding::kAscii;
    if (name == "binary") return PcdEncoding::kBinary;
    if (name == "binary_compressed") return PcdEncoding::kBinaryCompressed;
    return std::nullopt;
}

std::optional<PlyEncoding> parse_ply_encoding(std::string_view name) {
    if (name == "ascii") return PlyEncoding::kAscii;
    if (name == "binary" || name == "binary_little_endian") return PlyEncoding::kBinaryLittleEndian;
    return std::nullopt;
}

}  // namespace makeway::io

#pragma once
// A preflight of a ROS 1 bag's record structure (format 2.0), before rosbag_storage reads it, and
// of the byte layout of the messages the program reads. No ROS header: fuzzed with the parsers.
//
// Why: rosbag_storage trusts every length in the file. A record header that declares 4 GB, a chunk
// whose uncompressed size says 0xFFFFFFF0, or a bag header whose index_pos points into chunk data
// make it allocate what the length says: on a machine with less memory its Buffer asserts and the
// process aborts (exit 134, a staging folder left behind); elsewhere it reads gigabytes for
// nothing. This walk seeks from record to record, reading only headers and index records, and
// bounds every length by the file's size before rosbag sees the file. A compressed chunk (bz2, lz4)
// is inflated to the size it declares (bounded first) and its records walked the same way.
#include <cstddef>
#include <cstdint>
#include <filesystem>

namespace makeway::rosio {

struct BagCheckParams {
    /// A chunk's declared uncompressed size above this is refused: rosbag writes chunks of 768 KB
    /// (one message may exceed that: a 64-beam sweep is ~4 MB); 1 GiB is no real chunk.
    std::uint64_t max_chunk_bytes = std::uint64_t{1} << 30;
    /// Inflate compressed chunks and walk their records too (rosbag inflates each again to read
    /// it).
    bool walk_compressed = true;
};

struct BagCheckResult {
    std::uint64_t records = 0;  ///< top-level records walked
    std::uint64_t chunks = 0;
    std::uint64_t connections = 0;        ///< in the index (those inside chunks are not counted)
    std::uint64_t compressed_chunks = 0;  ///< inflated and walked
    std::uint64_t messages = 0;           ///< message records walked inside chunks
};

/// Throws io::FileError("PATH: record at byte N (KIND): problem") for the first length, offset or
/// field that does not fit the file; "not a regular file" for folders, FIFOs and devices.
BagCheckResult check_bag_structure(const std::filesystem::path& path,
                                   const BagCheckParams& params = {});

/// The serialized bytes of a sensor_msgs/PointCloud2 or a nav_msgs/Odometry walked against the
/// lengths they declare (strings, the field list, the data), before ROS's deserialiser sees them:
/// it resizes a vector to whatever length it reads (0xFFFFFFF0: bad_alloc) and only then finds the
/// bytes missing. Throws io::FormatError "WHAT needs N bytes, the message has M left", or for bytes
/// left over after the message's end.
void check_cloud_message(const std::uint8_t* data, std::size_t size);
void check_odometry_message(const std::uint8_t* data, std::size_t size);

}  // namespace makeway::rosio

#pragma once
// What PCD and PLY share: scalar types, the mapping from file fields onto PointCloud channels, and
// exact per-value encoding (binary bytes, shortest round-trip text).
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "makeway/common/point_cloud.hpp"

namespace makeway::io {

enum class ScalarType : std::uint8_t {
    kInt8,
    kUInt8,
    kInt16,
    kUInt16,
    kInt32,
    kUInt32,
    kFloat32,
    kFloat64
};
std::size_t scalar_size(ScalarType type);
std::string_view scalar_name(ScalarType type);

/// The PointCloud channel a file field maps onto; kNone for fields makeway does not keep.
enum class Channel : std::uint8_t {
    kX,
    kY,
    kZ,
    kIntensity,
    kRing,
    kTime,
    kLabel,
    kInstance,
    kNone
};

/// Accepts the canonical names and common aliases ("t" and "timestamp" for time).
Channel channel_for_name(std::string_view name);
std::string_view channel_name(Channel channel);
/// The type makeway stores and writes for a channel.
ScalarType native_type(Channel channel);
/// x, y, z, then every optional channel present, in a fixed order.
std::vector<Channel> channels_to_write(const PointFields& fields);
PointFields fields_of(const std::vector<Channel>& channels);

/// Decodes one binary scalar as a double (exact for every type but float64 > 2^53 integers).
double decode_scalar(const char* src, ScalarType type, bool big_endian = false);

/// Decodes one binary scalar into channel value i. Throws FormatError when the value does not fit
/// the channel (e.g. a negative ring). Values already in the native type are copied bit for bit.
void store_binary(PointCloud& cloud, Channel channel, std::size_t i, const char* src,
                  ScalarType type, bool big_endian = false);
/// Decodes n values of one field, the k-th at src + k * src_stride, into channel values 0..n-1.
/// Values in the native type are copied without conversion (the fast path for makeway's files).
void store_binary_column(PointCloud& cloud, Channel channel, const char* src,
                         std::size_t src_stride, std::size_t n, ScalarType type,
                         bool big_endian = false);

/// Parses a text token into channel value i. Throws FormatError on a malformed number.
void store_text(PointCloud& cloud, Channel channel, std::size_t i, std::string_view token);

/// Writes channel value i in the native type, little endian, to dst.
void load_binary(const PointCloud& cloud, Channel channel, std::size_t i, char* dst);
/// Appends channel value i as text that parses back to the same bits.
void append_text(const PointCloud& cloud, Channel channel, std::size_t i, std::string& out);

/// One text line per point: the channels' values separated by spaces (PCD and PLY ascii bodies).
void append_ascii_rows(const PointCloud& cloud, const std::vector<Channel>& channels,
                       std::string& out);

/// Problems shared by the readers: duplicate or missing coordinate fields. Throws FormatError.
void check_field_set(const std::vector<std::string>& names, const std::vector<Channel>& channels);

}  // namespace makeway::io

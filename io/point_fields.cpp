#include "io/point_fields.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>

#include "io/error.hpp"

namespace makeway::io {
namespace {

template <typename T>
T read_raw(const char* src, bool big_endian) {
    std::array<char, sizeof(T)> bytes;
    std::memcpy(bytes.data(), src, sizeof(T));
    if (big_endian) std::reverse(bytes.begin(), bytes.end());
    T value;
    std::memcpy(&value, bytes.data(), sizeof(T));
    return value;
}

}  // namespace

double decode_scalar(const char* src, ScalarType type, bool big_endian) {
    switch (type) {
        case ScalarType::kInt8:
            return read_raw<std::int8_t>(src, big_endian);
        case ScalarType::kUInt8:
            return read_raw<std::uint8_t>(src, big_endian);
        case ScalarType::kInt16:
            return read_raw<std::int16_t>(src, big_endian);
        case ScalarType::kUInt16:
            return read_raw<std::uint16_t>(src, big_endian);
        case ScalarType::kInt32:
            return read_raw<std::int32_t>(src, big_endian);
        case ScalarType::kUInt32:
            return read_raw<std::uint32_t>(src, big_endian);
        case ScalarType::kFloat32:
            return read_raw<float>(src, big_endian);
        case ScalarType::kFloat64:
            return read_raw<double>(src, big_endian);
    }
    return 0.0;
}

namespace {

template <typename T>
T checked_integer(double v, Channel channel) {
    if (!std::isfinite(v) || v != std::floor(v) ||
        v < static_cast<double>(std::numeric_limits<T>::min()) ||
        v > static_cast<double>(std::numeric_limits<T>::max())) {
        throw FormatError("field '" + std::string(channel_name(channel)) + "' value " +
                          std::to_string(v) + " does not fit " +
                          std::string(scalar_name(native_type(channel))));
    }
    return static_cast<T>(v);
}

void store_double(PointCloud& c, Channel channel, std::size_t i, double v) {
    switch (channel) {
        case Channel::kX:
            c.xyz[i].x() = static_cast<float>(v);
            break;
        case Channel::kY:
            c.xyz[i].y() = static_cast<float>(v);
            break;
        case Channel::kZ:
            c.xyz[i].z() = static_cast<float>(v);
            break;
        case Channel::kIntensity:
            c.intensity[i] = static_cast<float>(v);
            break;
        case Channel::kTime:
            c.time_s[i] = static_cast<float>(v);
            break;
        case Channel::kRing:
            c.ring[i] = checked_integer<std::uint16_t>(v, channel);
            break;
        case Channel::kLabel:
            c.label[i] = checked_integer<std::uint8_t>(v, channel);
            break;
        case Channel::kInstance:
            c.instance[i] = checked_integer<std::uint32_t>(v, channel);
            break;
        case Channel::kNone:
            break;
    }
}

float* float_slot(PointCloud& c, Channel channel, std::size_t i) {
    switch (channel) {
        case Channel::kX:
            return &c.xyz[i].x();
        case Channel::kY:
            return &c.xyz[i].y();
        case Channel::kZ:
            return &c.xyz[i].z();
        case Channel::kIntensity:
            return &c.intensity[i];
        case Channel::kTime:
            return &c.time_s[i];
        default:
            return nullptr;
    }
}

const char* value_bytes(const PointCloud& c, Channel channel, std::size_t i) {
    switch (channel) {
        case Channel::kX:
            return reinterpret_cast<const char*>(&c.xyz[i].x());
        case Channel::kY:
            return reinterpret_cast<const char*>(&c.xyz[i].y());
        case Channel::kZ:
            return reinterpret_cast<const char*>(&c.xyz[i].z());
        case Channel::kIntensity:
            return reinterpret_cast<const char*>(&c.intensity[i]);
        case Channel::kRing:
            return reinterpret_cast<const char*>(&c.ring[i]);
        case Channel::kTime:
            return reinterpret_cast<const char*>(&c.time_s[i]);
        case Channel::kLabel:
            return reinterpret_cast<const char*>(&c.label[i]);
        case Channel::kInstance:
            return reinterpret_cast<const char*>(&c.instance[i]);
        case Channel::kNone:
            break;
    }
    return nullptr;
}

FormatError bad_number(std::string_view token, Channel channel) {
    std::string shown(token.substr(0, 40));
    return FormatError("bad number '" + shown + "' in field '" +
                       std::string(channel_name(channel)) + "'");
}

}  // namespace

std::size_t scalar_size(ScalarType type) {
    constexpr std::array<std::size_t, 8> kSizes{1, 1, 2, 2, 4, 4, 4, 8};
    return kSizes[static_cast<std::size_t>(type)];
}

std::string_view scalar_name(ScalarType type) {
    constexpr std::array<std::string_view, 8> kNames{"int8",  "uint8",  "int16",   "uint16",
                                                     "int32", "uint32", "float32", "float64"};
    return kNames[static_cast<std::size_t>(type)];
}

Channel channel_for_name(std::string_view name) {
    if (name == "x") return Channel::kX;
    if (name == "y") return Channel::kY;
    if (name == "z") return Channel::kZ;
    if (name == "intensity") return Channel::kIntensity;
    if (name == "ring") return Channel::kRing;
    if (name == "time" || name == "t" || name == "timestamp") return Channel::kTime;
    if (name == "label") return Channel::kLabel;
    if (name == "instance") return Channel::kInstance;
    return Channel::kNone;
}

std::string_view channel_name(Channel channel) {
    constexpr std::array<std::string_view, 9> kNames{
        "x", "y", "z", "intensity", "ring", "time", "label", "instance", "(unused)"};
    return kNames[static_cast<std::size_t>(channel)];
}

ScalarType native_type(Channel channel) {
    switch (channel) {
        case Channel::kRing:
            return ScalarType::kUInt16;
        case Channel::kLabel:
            return ScalarType::kUInt8;
        case Channel::kInstance:
            return ScalarType::kUInt32;
        default:
            return ScalarType::kFloat32;
    }
}

std::vector<Channel> channels_to_write(const PointFields& f) {
    std::vector<Channel> out{Channel::kX, Channel::kY, Channel::kZ};
    if (f.intensity) out.push_back(Channel::kIntensity);
    if (f.ring) out.push_back(Channel::kRing);
    if (f.time) out.push_back(Channel::kTime);
    if (f.label) out.push_back(Channel::kLabel);
    if (f.instance) out.push_back(Channel::kInstance);
    return out;
}

PointFields fields_of(const std::vector<Channel>& channels) {
    PointFields f;
    for (Channel c : channels) {
        f.intensity |= c == Channel::kIntensity;
        f.ring |= c == Channel::kRing;
        f.time |= c == Channel::kTime;
        f.label |= c == Channel::kLabel;
        f.instance |= c == Channel::kInstance;
    }
    return f;
}

void store_binary(PointCloud& cloud, Channel channel, std::size_t i, const char* src,
                  ScalarType type, bool big_endian) {
    if (channel == Channel::kNone) return;
    if (type == native_type(channel) && !big_endian) {
        std::memcpy(const_cast<char*>(value_bytes(cloud, channel, i)), src, scalar_size(type));
        return;
    }
    store_double(cloud, channel, i, decode_scalar(src, type, big_endian));
}

void store_binary_column(PointCloud& cloud, Channel channel, const char* src,
                         std::size_t src_stride, std::size_t n, ScalarType type, bool big_endian) {
    if (channel == Channel::kNone || n == 0) return;
    if (type != native_type(channel) || big_endian) {
        for (std::size_t i = 0; i < n; ++i) {
            store_binary(cloud, channel, i, src + i * src_stride, type, big_endian);
        }
        return;
    }
    // Channel values are equally spaced in memory: xyz interleaved, the others packed.
    char* dst = const_cast<char*>(value_bytes(cloud, channel, 0));
    const std::size_t dst_stride =
        channel == Channel::kX || channel == Channel::kY || channel == Channel::kZ
            ? sizeof(Eigen::Vector3f)
            : scalar_size(type);
    const std::size_t size = scalar_size(type);
    for (std::size_t i = 0; i < n; ++i)
        std::memcpy(dst + i * dst_stride, src + i * src_stride, size);
}

void store_text(PointCloud& cloud, Channel channel, std::size_t i, std::string_view token) {
    if (channel == Channel::kNone) return;
    const char* first = token.data();
    const char* last = token.data() + token.size();
    if (float* slot = float_slot(cloud, channel, i)) {
        // Parse straight into float: via double would round twice.
        auto [ptr, ec] = std::from_chars(first, last, *slot);
        if (ec == std::errc::result_out_of_range) {
            *slot = static_cast<float>(std::strtod(std::string(token).c_str(), nullptr));
        } else if (ec != std::errc() || ptr != last) {
            throw bad_number(token, channel);
        }
        return;
    }
    std::int64_t integer = 0;
    auto [ptr, ec] = std::from_chars(first, last, integer);
    if (ec == std::errc() && ptr == last) {
        store_double(cloud, channel, i, static_cast<double>(integer));
        return;
    }
    double value = 0.0;
    auto [ptr2, ec2] = std::from_chars(first, last, value);
    if (ec2 != std::errc() || ptr2 != last) throw bad_number(token, channel);
    store_double(cloud, channel, i, value);
}

void load_binary(const PointCloud& cloud, Channel channel, std::size_t i, char* dst) {
    std::memcpy(dst, value_bytes(cloud, channel, i), scalar_size(native_type(channel)));
}

void append_text(const PointCloud& cloud, Channel channel, std::size_t i, std::string& out) {
    char buf[64];
    std::to_chars_result r{};
    switch (channel) {
        case Channel::kRing:
            r = std::to_chars(buf, buf + sizeof(buf), cloud.ring[i]);
            break;
        case Channel::kLabel:
            r = std::to_chars(buf, buf + sizeof(buf), +cloud.label[i]);
            break;
        case Channel::kInstance:
            r = std::to_chars(buf, buf + sizeof(buf), cloud.instance[i]);
            break;
        default: {
            float v = 0.0f;
            std::memcpy(&v, value_bytes(cloud, channel, i), sizeof(float));
            if (std::isnan(v)) {
                out += "nan";
                return;
            }
            r = std::to_chars(buf, buf + sizeof(buf), v);  // shortest round-trip form
        }
    }
    out.append(buf, r.ptr);
}

void append_ascii_rows(const PointCloud& cloud, const std::vector<Channel>& channels,
                       std::string& out) {
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        for (std::size_t k = 0; k < channels.size(); ++k) {
            if (k > 0) out += ' ';
            append_text(cloud, channels[k], i, out);
        }
        out += '\n';
    }
}

void check_field_set(const std::vector<std::string>& names, const std::vector<Channel>& channels) {
    for (std::size_t a = 0; a < channels.size(); ++a) {
        if (channels[a] == Channel::kNone) continue;
        for (std::size_t b = a + 1; b < channels.size(); ++b) {
            if (channels[a] == channels[b]) {
                throw FormatError("fields '" + names[a] + "' and '" + names[b] + "' both give " +
                                  std::string(channel_name(channels[a])));
            }
        }
    }
    for (Channel c : {Channel::kX, Channel::kY, Channel::kZ}) {
        if (std::find(channels.begin(), channels.end(), c) == channels.end()) {
            throw FormatError("no '" + std::string(channel_name(c)) + "' field");
        }
    }
}

}  // namespace makeway::io

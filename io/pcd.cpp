#include "io/pcd.hpp"

#include <lzf.h>

#include <array>
#include <cstring>
#include <limits>
#include <optional>

#include "io/error.hpp"
#include "io/point_fields.hpp"
#include "io/text_scan.hpp"

namespace makeway::io {
namespace {

constexpr std::size_t kMaxPcdHeaderBytes = 1 << 16;
constexpr std::uint64_t kMaxPoints = std::uint64_t{1} << 32;

struct PcdField {
    std::string name;
    std::size_t size = 0;
    char type = 'F';
    std::size_t count = 1;
    std::optional<ScalarType> scalar;  ///< nullopt for types makeway cannot decode (I8, U8)
    Channel channel = Channel::kNone;
};

struct PcdHeader {
    std::vector<PcdField> fields;
    std::uint64_t points = 0;
    std::string data;
    std::size_t data_offset = 0;
    std::size_t point_step = 0;
};

std::optional<ScalarType> scalar_for(char type, std::size_t size) {
    if (type == 'F' && size == 4) return ScalarType::kFloat32;
    if (type == 'F' && size == 8) return ScalarType::kFloat64;
    if (type == 'I' && size == 1) return ScalarType::kInt8;
    if (type == 'I' && size == 2) return ScalarType::kInt16;
    if (type == 'I' && size == 4) return ScalarType::kInt32;
    if (type == 'U' && size == 1) return ScalarType::kUInt8;
    if (type == 'U' && size == 2) return ScalarType::kUInt16;
    if (type == 'U' && size == 4) return ScalarType::kUInt32;
    return std::nullopt;
}

std::uint64_t header_count(const std::vector<std::string_view>& w, const char* key) {
    if (w.size() != 2) throw FormatError(std::string("header line ") + key + " needs one value");
    const auto v = parse_count(w[1]);
    if (!v)
        throw FormatError(std::string("header ") + key + " is not a count: '" +
                          std::string(w[1].substr(0, 40)) + "'");
    return *v;
}

void set_field_column(PcdHeader& h, const std::vector<std::string_view>& w, const char* key) {
    if (w.size() - 1 != h.fields.size()) {
        throw FormatError(std::string("header ") + key + " has " + std::to_string(w.size() - 1) +
                          " entries for " + std::to_string(h.fields.size()) + " FIELDS");
    }
    for (std::size_t i = 0; i < h.fields.size(); ++i) {
        const std::string_view v = w[i + 1];
        if (std::strcmp(key, "TYPE") == 0) {
            if (v.size() != 1 || (v[0] != 'F' && v[0] != 'I' && v[0] != 'U')) {
                throw FormatError("field '" + h.fields[i].name + "' has unknown TYPE '" +
                                  std::string(v.substr(0, 8)) + "'");
            }
            h.fields[i].type = v[0];
            continue;
        }
        const auto n = parse_count(v);
        if (!n || *n == 0 || *n > 4096) {
            throw FormatError("field '" + h.fields[i].name + "' has bad " + key + " '" +
                              std::string(v.substr(0, 16)) + "'");
        }
        (std::strcmp(key, "SIZE") == 0 ? h.fields[i].size : h.fields[i].count) = *n;
    }
}

PcdHeader parse_pcd_header(std::string_view bytes) {
    PcdHeader h;
    std::optional<std::uint64_t> width, height, points;
    bool have_size = false, have_type = false, first = true;
    std::size_t pos = 0;
    while (h.data.empty()) {
        if (pos > kMaxPcdHeaderBytes)
            throw FormatError("no DATA line in the first 64 KiB of header");
        const auto line = next_line(bytes, pos);
        if (!line) throw FormatError(first ? "not a PCD file" : "header ends before its DATA line");
        const auto w = split_words(*line);
        if (w.empty() || w[0].front() == '#') continue;
        const std::string_view key = w[0];
        if (first && key != "VERSION" && key != "FIELDS") {
            throw FormatError("not a PCD file (expected a VERSION or FIELDS header line)");
        }
        first = false;
        if (key == "VERSION" || key == "VIEWPOINT") {
            continue;
        } else if (key == "FIELDS") {
            if (w.size() < 2) throw FormatError("header FIELDS is empty");
            for (std::size_t i = 1; i < w.size(); ++i) {
                if (!is_header_name(w[i]))
                    throw FormatError("header FIELDS: field " + std::to_string(i) +
                                      " is not a printable ASCII name");
                PcdField f;
                f.name = std::string(w[i]);
                h.fields.push_back(f);
            }
        } else if (key == "SIZE" || key == "TYPE" || key == "COUNT") {
            if (h.fields.empty())
                throw FormatError("header " + std::string(key) + " before FIELDS");
            set_field_column(h, w, std::string(key).c_str());
            have_size |= key == "SIZE";
            have_type |= key == "TYPE";
        } else if (key == "WIDTH") {
            width = header_count(w, "WIDTH");
        } else if (key == "HEIGHT") {
            height = header_count(w, "HEIGHT");
        } else if (key == "POINTS") {
            points = header_count(w, "POINTS");
        } else if (key == "DATA") {
            if (w.size() != 2) throw FormatError("header DATA needs one value");
            h.data = std::string(w[1]);
            if (h.data != "ascii" && h.data != "binary" && h.data != "binary_compressed") {
                throw FormatError("unknown DATA encoding '" + std::string(w[1].substr(0, 32)) +
                                  "'");
            }
        } else {
            throw FormatError("unknown header line '" + std::string(key.substr(0, 32)) + "'");
        }
    }
    h.data_offset = pos;
    if (h.fields.empty()) throw FormatError("header has no FIELDS");
    if (!have_size || !have_type) throw FormatError("header lacks SIZE or TYPE");
    if (!width) throw FormatError("header has no WIDTH");
    const std::uint64_t rows = height.value_or(1);
    if (rows != 0 && *width > kMaxPoints / rows) throw FormatError("WIDTH x HEIGHT is too large");
    h.points = points.value_or(*width * rows);
    if (h.points != *width * rows) {
        throw FormatError("POINTS " + std::to_string(h.points) + " != WIDTH x HEIGHT " +
                          std::to_string(*width * rows));
    }
    if (h.points > kMaxPoints)
        throw FormatError("POINTS " + std::to_string(h.points) + " is too large");

    std::vector<std::string> names;
    std::vector<Channel> channels;
    for (PcdField& f : h.fields) {
        f.scalar = scalar_for(f.type, f.size);
        if (f.type == 'F' && f.size != 4 && f.size != 8) {
            throw FormatError("field '" + f.name + "' has TYPE F with SIZE " +
                              std::to_string(f.size));
        }
        if (f.size != 1 && f.size != 2 && f.size != 4 && f.size != 8) {
            throw FormatError("field '" + f.name + "' has SIZE " + std::to_string(f.size));
        }
        f.channel = channel_for_name(f.name);
        if (f.channel != Channel::kNone && (f.count != 1 || !f.scalar)) {
            throw FormatError("field '" + f.name + "' must be one scalar of at most 4 bytes or F8");
        }
        h.point_step += f.size * f.count;
        names.push_back(f.name);
        channels.push_back(f.channel);
    }
    check_field_set(names, channels);
    return h;
}

CloudFile make_result(const PcdHeader& h) {
    CloudFile out;
    out.info.format = "pcd";
    out.info.encoding = h.data;
    std::vector<Channel> channels;
    for (const PcdField& f : h.fields) {
        out.info.fields.push_back(f.name);
        if (f.channel == Channel::kNone) out.info.ignored_fields.push_back(f.name);
        channels.push_back(f.channel);
    }
    out.cloud.resize(static_cast<std::size_t>(h.points), fields_of(channels));
    return out;
}

void read_ascii(const PcdHeader& h, std::string_view body, PointCloud& cloud) {
    TokenStream tokens(body);
    for (std::size_t i = 0; i < h.points; ++i) {
        for (const PcdField& f : h.fields) {
            for (std::size_t k = 0; k < f.count; ++k) {
                const auto t = tokens.next();
                if (!t) {
                    throw FormatError("truncated: POINTS declares " + std::to_string(h.points) +
                                      ", data ends in point " + std::to_string(i));
                }
                store_text(cloud, f.channel, i, *t);
            }
        }
    }
    if (!tokens.at_end()) throw FormatError("more data than POINTS declares");
}

// Fields laid out either point by point (binary) or field by field (binary_compressed).
void read_binary(const PcdHeader& h, const char* data, bool field_major, PointCloud& cloud) {
    std::size_t field_start = 0;
    for (const PcdField& f : h.fields) {
        const std::size_t field_bytes = f.size * f.count;
        if (f.channel != Channel::kNone) {
            const char* first = data + (field_major ? field_start * h.points : field_start);
            store_binary_column(cloud, f.channel, first, field_major ? field_bytes : h.point_step,
                                static_cast<std::size_t>(h.points), *f.scalar);
        }
        field_start += field_bytes;
    }
}

std::string size_mismatch(const PcdHeader& h, std::size_t expected, std::size_t found) {
    return "data size mismatch: " + std::to_string(h.points) + " points of " +
           std::to_string(h.point_step) + " bytes need " + std::to_string(expected) +
           " bytes, found " + std::to_string(found);
}

}  // namespace

CloudFile parse_pcd(std::string_view bytes) {
    const PcdHeader h = parse_pcd_header(bytes);
    const std::string_view body = bytes.substr(h.data_offset);
    if (h.data == "ascii") {
        // At least two characters per value: guards the allocation against huge POINTS.
        if (h.points > body.size())
            throw FormatError("truncated: POINTS " + std::to_string(h.points) + " but only " +
                              std::to_string(body.size()) + " bytes of data");
        CloudFile out = make_result(h);
        read_ascii(h, body, out.cloud);
        return out;
    }
    if (h.point_step > 0 && h.points > std::numeric_limits<std::size_t>::max() / h.point_step) {
        throw FormatError("POINTS x point size overflows");
    }
    const std::size_t expected = static_cast<std::size_t>(h.points) * h.point_step;
    if (h.data == "binary") {
        if (body.size() != expected) throw FormatError(size_mismatch(h, expected, body.size()));
        CloudFile out = make_result(h);
        read_binary(h, body.data(), false, out.cloud);
        return out;
    }
    // binary_compressed: uint32 compressed size, uint32 uncompressed size, LZF data (field-major).
    if (body.size() < 8)
        throw FormatError("truncated: binary_compressed data lacks its size words");
    std::uint32_t compressed = 0, uncompressed = 0;
    std::memcpy(&compressed, body.data(), 4);
    std::memcpy(&uncompressed, body.data() + 4, 4);
    if (uncompressed != expected) throw FormatError(size_mismatch(h, expected, uncompressed));
    if (compressed != body.size() - 8) {
        throw FormatError("compressed size " + std::to_string(compressed) + " but " +
                          std::to_string(body.size() - 8) + " bytes follow the header");
    }
    if (uncompressed > 128ull * compressed + 1024) {
        throw FormatError("uncompressed size " + std::to_string(uncompressed) +
                          " is impossible for " + std::to_string(compressed) + " compressed bytes");
    }
    std::string raw(uncompressed, '\0');
    if (uncompressed > 0) {
        const unsigned n = lzf_decompress(body.data() + 8, compressed, raw.data(), uncompressed);
        if (n != uncompressed) throw FormatError("corrupt LZF data");
    }
    CloudFile out = make_result(h);
    read_binary(h, raw.data(), true, out.cloud);
    return out;
}

std::string serialize_pcd(const PointCloud& cloud, PcdEncoding encoding) {
    const std::vector<Channel> channels = channels_to_write(cloud.fields());
    const std::size_t n = cloud.size();
    std::string fields, sizes, types, counts;
    std::size_t point_step = 0;
    for (Channel c : channels) {
        const ScalarType t = native_type(c);
        fields += " " + std::string(channel_name(c));
        sizes += " " + std::to_string(scalar_size(t));
        types += t == ScalarType::kFloat32 ? " F" : " U";
        counts += " 1";
        point_step += scalar_size(t);
    }
    const char* data_name = encoding == PcdEncoding::kAscii    ? "ascii"
                            : encoding == PcdEncoding::kBinary ? "binary"
                                                               : "binary_compressed";
    std::string out = "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS" + fields +
                      "\nSIZE" + sizes + "\nTYPE" + types + "\nCOUNT" + counts + "\nWIDTH " +
                      std::to_string(n) + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " +
                      std::to_string(n) + "\nDATA " + data_name + "\n";
    if (encoding == PcdEncoding::kAscii) {
        append_ascii_rows(cloud, channels, out);
        return out;
    }
    std::string raw(n * point_step, '\0');
    std::size_t field_start = 0;
    for (Channel c : channels) {
        const std::size_t size = scalar_size(native_type(c));
        for (std::size_t i = 0; i < n; ++i) {
            const std::size_t offset = encoding == PcdEncoding::kBinary
                                           ? i * point_step + field_start
                                           : field_start * n + i * size;
            load_binary(cloud, c, i, raw.data() + offset);
        }
        field_start += size;
    }
    if (encoding == PcdEncoding::kBinary) return out + raw;

    if (raw.size() > std::numeric_limits<std::uint32_t>::max()) {
        throw std::length_error("PCD binary_compressed holds at most 4 GiB of point data");
    }
    std::string packed(raw.size() + raw.size() / 8 + 64, '\0');
    unsigned compressed = 0;
    if (!raw.empty()) {
        compressed = lzf_compress(raw.data(), static_cast<unsigned>(raw.size()), packed.data(),
                                  static_cast<unsigned>(packed.size()));
        if (compressed == 0) throw std::runtime_error("LZF compression failed");
    }
    const auto sizes_word = std::array<std::uint32_t, 2>{static_cast<std::uint32_t>(compressed),
                                                         static_cast<std::uint32_t>(raw.size())};
    out.append(reinterpret_cast<const char*>(sizes_word.data()), 8);
    out.append(packed.data(), compressed);
    return out;
}

}  // namespace makeway::io

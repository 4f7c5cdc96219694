#include "io/ply.hpp"

#include <algorithm>
#include <limits>
#include <optional>

#include "io/error.hpp"
#include "io/point_fields.hpp"
#include "io/text_scan.hpp"

namespace makeway::io {
namespace {

constexpr std::size_t kMaxPlyHeaderBytes = 1 << 16;

struct PlyProperty {
    std::string name;
    ScalarType type = ScalarType::kFloat32;
    bool is_list = false;
    ScalarType count_type = ScalarType::kUInt8;
    Channel channel = Channel::kNone;
};

struct PlyElement {
    std::string name;
    std::uint64_t count = 0;
    std::vector<PlyProperty> properties;
};

enum class Encoding { kAscii, kLittle, kBig };

struct PlyHeader {
    Encoding encoding = Encoding::kAscii;
    std::vector<PlyElement> elements;
    std::size_t data_offset = 0;
};

std::optional<ScalarType> ply_type(std::string_view name) {
    if (name == "char" || name == "int8") return ScalarType::kInt8;
    if (name == "uchar" || name == "uint8") return ScalarType::kUInt8;
    if (name == "short" || name == "int16") return ScalarType::kInt16;
    if (name == "ushort" || name == "uint16") return ScalarType::kUInt16;
    if (name == "int" || name == "int32") return ScalarType::kInt32;
    if (name == "uint" || name == "uint32") return ScalarType::kUInt32;
    if (name == "float" || name == "float32") return ScalarType::kFloat32;
    if (name == "double" || name == "float64") return ScalarType::kFloat64;
    return std::nullopt;
}

std::string_view ply_type_name(ScalarType t) {
    constexpr std::string_view kNames[] = {"char", "uchar", "short", "ushort",
                                           "int",  "uint",  "float", "double"};
    return kNames[static_cast<std::size_t>(t)];
}

ScalarType require_type(std::string_view name) {
    const auto t = ply_type(name);
    if (!t)
        throw FormatError("unknown PLY property type '" + std::string(name.substr(0, 32)) + "'");
    return *t;
}

PlyProperty parse_property(const std::vector<std::string_view>& w) {
    PlyProperty p;
    if (w.size() == 3) {
        p.type = require_type(w[1]);
        p.name = std::string(w[2]);
    } else if (w.size() == 5 && w[1] == "list") {
        p.is_list = true;
        p.count_type = require_type(w[2]);
        p.type = require_type(w[3]);
        p.name = std::string(w[4]);
        if (p.count_type == ScalarType::kFloat32 || p.count_type == ScalarType::kFloat64) {
            throw FormatError("list property '" + p.name + "' has a floating-point count type");
        }
    } else {
        throw FormatError("malformed property line");
    }
    if (!is_header_name(p.name)) throw FormatError("a property name is not printable ASCII");
    return p;
}

PlyHeader parse_ply_header(std::string_view bytes) {
    PlyHeader h;
    std::size_t pos = 0;
    auto first = next_line(bytes, pos);
    if (!first || split_words(*first) != std::vector<std::string_view>{"ply"}) {
        throw FormatError("not a PLY file (first line is not 'ply')");
    }
    bool have_format = false;
    while (true) {
        if (pos > kMaxPlyHeaderBytes) throw FormatError("no end_header in the first 64 KiB");
        const auto line = next_line(bytes, pos);
        if (!line) throw FormatError("header ends before end_header");
        const auto w = split_words(*line);
        if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
        if (w[0] == "end_header") break;
        if (w[0] == "format") {
            if (w.size() != 3 || w[2] != "1.0") throw FormatError("malformed format line");
            if (w[1] == "ascii")
                h.encoding = Encoding::kAscii;
            else if (w[1] == "binary_little_endian")
                h.encoding = Encoding::kLittle;
            else if (w[1] == "binary_big_endian")
                h.encoding = Encoding::kBig;
            else
                throw FormatError("unknown PLY format '" + std::string(w[1].substr(0, 32)) + "'");
            have_format = true;
        } else if (w[0] == "element") {
            const auto n = w.size() == 3 ? parse_count(w[2]) : std::nullopt;
            if (!n) throw FormatError("malformed element line");
            h.elements.push_back({std::string(w[1]), *n, {}});
        } else if (w[0] == "property") {
            if (h.elements.empty()) throw FormatError("property before any element");
            h.elements.back().properties.push_back(parse_property(w));
        } else {
            throw FormatError("unknown header line '" + std::string(w[0].substr(0, 32)) + "'");
        }
    }
    if (!have_format) throw FormatError("header has no format line");
    h.data_offset = pos;
    return h;
}

// Bounds-checked reader over the binary body.
class ByteCursor {
  public:
    ByteCursor(std::string_view data, bool big_endian) : data_(data), big_(big_endian) {}
    const char* take(std::size_t n) {
        if (data_.size() - pos_ < n) throw FormatError("truncated: data ends inside an element");
        const char* p = data_.data() + pos_;
        pos_ += n;
        return p;
    }
    std::size_t take_count(ScalarType t) {
        const double n = decode_scalar(take(scalar_size(t)), t, big_);
        if (!(n >= 0.0) || n > static_cast<double>(remaining())) {
            throw FormatError("bad list length " + std::to_string(n));
        }
        return static_cast<std::size_t>(n);
    }
    std::size_t remaining() const { return data_.size() - pos_; }
    bool big_endian() const { return big_; }

  private:
    std::string_view data_;
    std::size_t pos_ = 0;
    bool big_;
};

void read_binary_element(const PlyElement& e, ByteCursor& cur, PointCloud* cloud,
                         PointFields fields) {
    std::size_t min_bytes = 0;
    for (const auto& p : e.properties) min_bytes += scalar_size(p.is_list ? p.count_type : p.type);
    if (min_bytes > 0 && e.count > cur.remaining() / min_bytes) {
        throw FormatError("truncated: element '" + e.name + "' declares " +
                          std::to_string(e.count) + " entries but only " +
                          std::to_string(cur.remaining()) + " bytes remain");
    }
    if (cloud) cloud->resize(static_cast<std::size_t>(e.count), fields);
    const bool fixed_size = std::none_of(e.properties.begin(), e.properties.end(),
                                         [](const PlyProperty& p) { return p.is_list; });
    if (fixed_size) {  // one block, decoded column by column
        const auto n = static_cast<std::size_t>(e.count);
        const char* block = cur.take(n * min_bytes);
        std::size_t offset = 0;
        for (const auto& p : e.properties) {
            if (cloud) {
                store_binary_column(*cloud, p.channel, block + offset, min_bytes, n, p.type,
                                    cur.big_endian());
            }
            offset += scalar_size(p.type);
        }
        return;
    }
    for (std::size_t i = 0; i < e.count; ++i) {
        for (const auto& p : e.properties) {
            if (p.is_list) {
                const std::size_t n = cur.take_count(p.count_type);
                if (n > cur.remaining() / scalar_size(p.type)) {
                    throw FormatError("truncated: list in '" + e.name + "' runs past the data");
                }
                cur.take(n * scalar_size(p.type));
            } else {
                const char* src = cur.take(scalar_size(p.type));
                if (cloud) store_binary(*cloud, p.channel, i, src, p.type, cur.big_endian());
            }
        }
    }
}

void read_ascii_element(const PlyElement& e, TokenStream& tokens, std::size_t body_size,
                        PointCloud* cloud, PointFields fields) {
    if (e.count > body_size / 2 + 1) {
        throw FormatError("truncated: element '" + e.name + "' declares " +
                          std::to_string(e.count) + " entries in " + std::to_string(body_size) +
                          " bytes");
    }
    if (cloud) cloud->resize(static_cast<std::size_t>(e.count), fields);
    auto next = [&]() {
        const auto t = tokens.next();
        if (!t) throw FormatError("truncated: data ends inside element '" + e.name + "'");
        return *t;
    };
    for (std::size_t i = 0; i < e.count; ++i) {
        for (const auto& p : e.properties) {
            if (p.is_list) {
                const auto n = parse_count(next());
                if (!n || *n > body_size) throw FormatError("bad list length in '" + e.name + "'");
                for (std::uint64_t k = 0; k < *n; ++k) next();
            } else {
                const std::string_view t = next();
                if (cloud) store_text(*cloud, p.channel, i, t);
            }
        }
    }
}

}  // namespace

CloudFile parse_ply(std::string_view bytes) {
    PlyHeader h = parse_ply_header(bytes);
    PlyElement* vertex = nullptr;
    for (auto& e : h.elements) {
        if (e.name == "vertex") vertex = &e;
    }
    if (!vertex) throw FormatError("no vertex element");

    CloudFile out;
    out.info.format = "ply";
    out.info.encoding = h.encoding == Encoding::kAscii    ? "ascii"
                        : h.encoding == Encoding::kLittle ? "binary_little_endian"
                                                          : "binary_big_endian";
    std::vector<std::string> names;
    std::vector<Channel> channels;
    for (auto& p : vertex->properties) {
        p.channel = p.is_list ? Channel::kNone : channel_for_name(p.name);
        out.info.fields.push_back(p.name);
        if (p.channel == Channel::kNone) out.info.ignored_fields.push_back(p.name);
        names.push_back(p.name);
        channels.push_back(p.channel);
    }
    check_field_set(names, channels);
    const PointFields fields = fields_of(channels);

    // Every element is walked, and the data must end where the header says: a header that
    // declares 5 vertices over 10, or `uchar x` over float data, is caught here instead of read
    // as garbage (the devices' own files end exactly).
    const std::string_view body = bytes.substr(h.data_offset);
    if (h.encoding == Encoding::kAscii) {
        TokenStream tokens(body);
        for (const auto& e : h.elements)
            read_ascii_element(e, tokens, body.size(), &e == vertex ? &out.cloud : nullptr, fields);
        if (!tokens.at_end())
            throw FormatError("data continues after the elements the header declares");
    } else {
        ByteCursor cur(body, h.encoding == Encoding::kBig);
        for (const auto& e : h.elements)
            read_binary_element(e, cur, &e == vertex ? &out.cloud : nullptr, fields);
        if (cur.remaining() != 0) {
            throw FormatError(std::to_string(cur.remaining()) +
                              " bytes after the elements the header declares");
        }
    }
    return out;
}

std::string serialize_ply(const PointCloud& cloud, PlyEncoding encoding) {
    const std::vector<Channel> channels = channels_to_write(cloud.fields());
    const std::size_t n = cloud.size();
    std::string out = "ply\nformat ";
    out += encoding == PlyEncoding::kAscii ? "ascii" : "binary_little_endian";
    out += " 1.0\ncomment written by makeway\nelement vertex " + std::to_string(n) + "\n";
    std::size_t point_step = 0;
    for (Channel c : channels) {
        out += "property " + std::string(ply_type_name(native_type(c))) + " " +
               std::string(channel_name(c)) + "\n";
        point_step += scalar_size(native_type(c));
    }
    out += "end_header\n";
    if (encoding == PlyEncoding::kAscii) {
        append_ascii_rows(cloud, channels, out);
        return out;
    }
    const std::size_t header_size = out.size();
    out.resize(header_size + n * point_step);
    char* dst = out.data() + header_size;
    for (std::size_t i = 0; i < n; ++i) {
        for (Channel c : channels) {
            load_binary(cloud, c, i, dst);
            dst += scalar_size(native_type(c));
        }
    }
    return out;
}

}  // namespace makeway::io

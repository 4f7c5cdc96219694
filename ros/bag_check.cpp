#include "ros/bag_check.hpp"

#include <bzlib.h>
#include <roslz4/lz4s.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "io/error.hpp"

namespace makeway::rosio {
namespace {

namespace fs = std::filesystem;

// Record kinds of the format (http://wiki.ros.org/Bags/Format/2.0).
constexpr std::uint8_t kMessageData = 0x02, kBagHeader = 0x03, kIndexData = 0x04, kChunk = 0x05,
                       kChunkInfo = 0x06, kConnection = 0x07;
// Record headers hold a few short fields (op, conn, topic, times); connection records carry the
// message definition in their data, tens of KB. Anything larger is damage, not a bag.
constexpr std::uint32_t kMaxHeaderBytes = 1u << 20;
constexpr std::uint32_t kMaxConnectionBytes = 16u << 20;

std::string kind_of(std::uint8_t op) {
    switch (op) {
        case kMessageData:
            return "message data";
        case kBagHeader:
            return "bag header";
        case kIndexData:
            return "index data";
        case kChunk:
            return "chunk";
        case kChunkInfo:
            return "chunk info";
        case kConnection:
            return "connection";
        default:
            return "op " + std::to_string(op);
    }
}

template <typename T>
T little(const std::string& bytes) {
    T v{};
    std::memcpy(&v, bytes.data(), sizeof(T));
    return v;
}

struct Record {
    std::uint64_t pos = 0;
    std::uint8_t op = 0;
    std::map<std::string, std::string> fields;
    std::uint64_t data_pos = 0;
    std::uint32_t data_len = 0;
};

class Walker {
  public:
    Walker(const fs::path& path, std::uint64_t size)
        : path_(path), size_(size), in_(path, std::ios::binary) {
        if (!in_) fail("cannot open for reading");
    }
    // The records of an inflated chunk (its first `size` bytes of `chunk_data`, which must outlive
    // the walker), their bytes counted from the chunk's data; each problem starts with `context`.
    Walker(const fs::path& path, const std::string& chunk_data, std::uint64_t size,
           std::string context)
        : path_(path), size_(size), memory_(&chunk_data), context_(std::move(context)) {}

    [[noreturn]] void fail(const std::string& problem) const {
        throw io::FileError(path_.string(), context_ + problem);
    }
    [[noreturn]] void fail_at(const Record& r, const std::string& problem) const {
        fail("record at byte " + std::to_string(r.pos) + " (" + kind_of(r.op) + "): " + problem);
    }

    // `n` bytes at `pos`, which must lie before `end` (the file's or an enclosing chunk's end).
    std::string bytes(std::uint64_t pos, std::uint64_t n, std::uint64_t end,
                      const std::string& what) {
        if (pos > end || n > end - pos) {
            fail("at byte " + std::to_string(pos) + ": " + what + " of " + std::to_string(n) +
                 " bytes runs past " +
                 (end == size_ && !memory_
                      ? "the end of the file (" + std::to_string(size_) + " bytes; cut short?)"
                      : "the end of its chunk"));
        }
        if (memory_)
            return memory_->substr(static_cast<std::size_t>(pos), static_cast<std::size_t>(n));
        std::string out;
        read_into(pos, n, out);
        return out;
    }
    // The same from the file into `out` (its capacity reused: chunks are read one after another).
    void read_into(std::uint64_t pos, std::uint64_t n, std::string& out) {
        out.resize(static_cast<std::size_t>(n));
        in_.seekg(static_cast<std::streamoff>(pos));
        if (!in_.read(out.data(), static_cast<std::streamsize>(n)))
            fail("read error at byte " + std::to_string(pos));
    }

    // name=value fields, each behind its 4-byte length, filling `text` exactly.
    std::map<std::string, std::string> fields(const std::string& text, std::uint64_t pos) {
        std::map<std::string, std::string> out;
        std::size_t at = 0;
        while (at < text.size()) {
            if (text.size() - at < 4)
                fail("record at byte " + std::to_string(pos) +
                     ": a header field's length is cut short");
            const auto len = little<std::uint32_t>(text.substr(at, 4));
            at += 4;
            if (len > text.size() - at) {
                fail("record at byte " + std::to_string(pos) + ": a header field declares " +
                     std::to_string(len) + " bytes, more than its header holds");
            }
            const std::string field = text.substr(at, len);
            at += len;
            const std::size_t eq = field.find('=');
            if (eq == std::string::npos)
                fail("record at byte " + std::to_string(pos) + ": a header field has no '='");
            out[field.substr(0, eq)] = field.substr(eq + 1);
        }
        return out;
    }

    Record record(std::uint64_t pos, std::uint64_t end) {
        Record r;
        r.pos = pos;
        const auto header_len = little<std::uint32_t>(bytes(pos, 4, end, "the header length"));
        if (header_len > kMaxHeaderBytes) {
            fail("record at byte " + std::to_string(pos) + ": declares a header of " +
                 std::to_string(header_len) + " bytes (record headers are small; damaged?)");
        }
        r.fields = fields(bytes(pos + 4, header_len, end, "the header"), pos);
        const auto op = r.fields.find("op");
        if (op == r.fields.end() || op->second.size() != 1)
            fail("record at byte " + std::to_string(pos) + ": no one-byte 'op' field");
        r.op = static_cast<std::uint8_t>(op->second[0]);
        r.data_pos = pos + 4 + header_len + 4;
        r.data_len = little<std::uint32_t>(bytes(pos + 4 + header_len, 4, end, "the data length"));
        if (r.data_len > end - std::min(end, r.data_pos)) {
            fail_at(r, "declares " + std::to_string(r.data_len) +
                           " bytes of data, past the end of " +
                           (end == size_ && !memory_
                                ? "the file (" + std::to_string(size_) + " bytes; cut short?)"
                                : "its chunk"));
        }
        return r;
    }

    template <typename T>
    T field(const Record& r, const std::string& name) const {
        const auto it = r.fields.find(name);
        if (it == r.fields.end()) fail_at(r, "no '" + name + "' field");
        if (it->second.size() != sizeof(T)) {
            fail_at(r, "field '" + name + "' holds " + std::to_string(it->second.size()) +
                           " bytes, not " + std::to_string(sizeof(T)));
        }
        return little<T>(it->second);
    }

    std::uint64_t size() const { return size_; }

  private:
    fs::path path_;
    std::uint64_t size_;
    const std::string* memory_ = nullptr;
    std::string context_;
    std::ifstream in_;
};

// A chunk's records, [begin, end) in `w`: messages and connections only; each start (from
// `begin`) into `starts`.
void walk_chunk(Walker& w, std::uint64_t begin, std::uint64_t end, std::set<std::uint32_t>& starts,
                BagCheckResult& out) {
    for (std::uint64_t inner = begin; inner < end;) {
        const Record m = w.record(inner, end);
        if (m.op != kMessageData && m.op != kConnection)
            w.fail_at(m, "not a message or connection inside a chunk");
        if (m.op == kMessageData) ++out.messages;
        starts.insert(static_cast<std::uint32_t>(inner - begin));
        inner = m.data_pos + m.data_len;
    }
}

// A compressed chunk's data inflated into `raw` (its first `size` bytes; the buffer only grows, one
// allocation for the whole bag), exactly the `size` it declares (the caller bounded it). lz4
// cannot expand more than 255-fold: a larger declared size is refused before any allocation.
void decompress(const std::string& compression, std::string& packed, std::uint64_t size,
                std::string& raw, const std::function<void(const std::string&)>& fail) {
    if (compression == "lz4" && size > 255 * static_cast<std::uint64_t>(packed.size()) + 64) {
        fail("declares " + std::to_string(size) + " bytes from " + std::to_string(packed.size()) +
             " lz4 bytes, more than lz4 expands to");
    }
    if (raw.size() < size + 1)
        raw.resize(static_cast<std::size_t>(size) + 1);  // one spare: a longer stream shows
    unsigned int got = static_cast<unsigned int>(size) + 1;
    const int rc =
        compression == "bz2"
            ? BZ2_bzBuffToBuffDecompress(raw.data(), &got, packed.data(),
                                         static_cast<unsigned int>(packed.size()), 0, 0)
            : roslz4_buffToBuffDecompress(packed.data(), static_cast<unsigned int>(packed.size()),
                                          raw.data(), &got);
    const bool full = compression == "bz2" ? rc == BZ_OUTBUFF_FULL : rc == ROSLZ4_OUTPUT_SMALL;
    if (full || (rc == (compression == "bz2" ? BZ_OK : ROSLZ4_OK) && got != size)) {
        fail("its " + compression + " data does not inflate to the " + std::to_string(size) +
             " bytes it declares" + (full ? " (more)" : " (" + std::to_string(got) + ")"));
    }
    if (rc != (compression == "bz2" ? BZ_OK : ROSLZ4_OK)) {
        fail("its " + compression + " data is damaged (the decompressor's error " +
             std::to_string(rc) + ")");
    }
}

// Serialized ROS message bytes, read against the lengths they declare.
class Cursor {
  public:
    Cursor(const std::uint8_t* data, std::size_t size) : left_(size), p_(data) {}
    void skip(std::uint64_t n, const std::string& what) {
        if (n > left_) {
            throw io::FormatError(what + " needs " + std::to_string(n) +
                                  " bytes, the message has " + std::to_string(left_) + " left");
        }
        p_ += n;
        left_ -= static_cast<std::size_t>(n);
    }
    std::uint32_t u32(const std::string& what) {
        const std::uint8_t* at = p_;
        skip(4, what);
        std::uint32_t v;
        std::memcpy(&v, at, 4);
        return v;
    }
    void string(const std::string& what) { skip(u32(what), what); }
    void header() {
        skip(12, "the header");
        string("header.frame_id");
    }
    void end(const std::string& type) const {
        if (left_ != 0)
            throw io::FormatError(std::to_string(left_) + " bytes after the end of a " + type);
    }

  private:
    std::size_t left_;
    const std::uint8_t* p_;
};

}  // namespace

void check_cloud_message(const std::uint8_t* data, std::size_t size) {
    Cursor c(data, size);
    c.header();
    c.skip(8, "height and width");
    const std::uint32_t fields = c.u32("the field count");
    for (std::uint32_t k = 0; k < fields; ++k) {
        c.string("field " + std::to_string(k) + "'s name");
        c.skip(9, "field " + std::to_string(k));
    }
    c.skip(9, "is_bigendian, point_step and row_step");
    c.string("data");
    c.skip(1, "is_dense");
    c.end("sensor_msgs/PointCloud2");
}

void check_odometry_message(const std::uint8_t* data, std::size_t size) {
    Cursor c(data, size);
    c.header();
    c.string("child_frame_id");
    c.skip(85 * 8, "the pose, twist and covariances");
    c.end("nav_msgs/Odometry");
}

BagCheckResult check_bag_structure(const fs::path& path, const BagCheckParams& params) {
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (!fs::exists(st)) throw io::FileError(path.string(), "no such bag file");
    if (!fs::is_regular_file(st)) {
        throw io::FileError(path.string(),
                            fs::is_directory(st)
                                ? "is a folder, not a bag file"
                                : "is not a regular file (a bag is read by seeking)");
    }
    const std::uint64_t size = fs::file_size(path, ec);
    if (ec) throw io::FileError(path.string(), "cannot read its size: " + ec.message());
    Walker w(path, size);
    const std::string magic = "#ROSBAG V2.0\n";
    if (size < magic.size())
        throw io::FileError(
            path.string(), "not a ROS 1 bag (" + std::to_string(size) + " bytes, no version line)");
    const std::string head = w.bytes(0, magic.size(), size, "the version line");
    if (head != magic) {
        if (head.rfind("#ROSBAG V", 0) == 0) {
            throw io::FileError(path.string(), "bag format " + head.substr(9, head.find('\n') - 9) +
                                                   " is not supported (2.0 only)");
        }
        throw io::FileError(path.string(), "not a ROS 1 bag (no #ROSBAG V2.0 line)");
    }

    BagCheckResult out;
    std::uint64_t index_pos = 0;
    std::uint32_t conn_count = 0, chunk_count = 0;
    std::map<std::uint64_t, std::uint8_t> op_at;  // every top-level record's start
    std::set<std::uint64_t> chunk_starts;
    std::uint64_t chunk_size = 0;         // the last chunk's uncompressed size
    std::set<std::uint32_t> chunk_inner;  // its records' offsets, when walked
    bool chunk_seen = false, chunk_compressed = false;
    std::string packed, raw;  // a compressed chunk's bytes and what they inflate to
    for (std::uint64_t pos = magic.size(); pos < size;) {
        const Record r = w.record(pos, size);
        op_at[pos] = r.op;
        ++out.records;
        if (out.records == 1) {
            if (r.op != kBagHeader) w.fail_at(r, "the first record must be the bag header");
            index_pos = w.field<std::uint64_t>(r, "index_pos");
            conn_count = w.field<std::uint32_t>(r, "conn_count");
            chunk_count = w.field<std::uint32_t>(r, "chunk_count");
        } else if (r.op == kBagHeader) {
            w.fail_at(r, "a second bag header");
        } else if (r.op == kChunk) {
            const auto compression =
                r.fields.count("compression") ? r.fields.at("compression") : std::string();
            if (compression != "none" && compression != "bz2" && compression != "lz4") {
                w.fail_at(r, "unknown compression '" + compression + "' (none, bz2 or lz4)");
            }
            chunk_size = w.field<std::uint32_t>(r, "size");
            if (chunk_size > params.max_chunk_bytes) {
                w.fail_at(r, "declares " + std::to_string(chunk_size) +
                                 " bytes uncompressed, more than the " +
                                 std::to_string(params.max_chunk_bytes) + " a chunk can hold here");
            }
            chunk_seen = true;
            chunk_compressed = compression != "none";
            chunk_inner.clear();
            chunk_starts.insert(pos);
            ++out.chunks;
            if (!chunk_compressed) {
                if (chunk_size != r.data_len) {
                    w.fail_at(r, "uncompressed, holds " + std::to_string(r.data_len) +
                                     " bytes but declares " + std::to_string(chunk_size));
                }
                walk_chunk(w, r.data_pos, r.data_pos + r.data_len, chunk_inner, out);
            } else if (params.walk_compressed) {
                // rosbag trusts the lengths inside a chunk as much as outside: inflated here first
                // (each chunk a second time: what it costs is in the README).
                w.read_into(r.data_pos, r.data_len, packed);  // record() bounded it by the file
                decompress(compression, packed, chunk_size, raw,
                           [&](const std::string& p) { w.fail_at(r, p); });
                Walker inner(path, raw, chunk_size,
                             "chunk at byte " + std::to_string(pos) + ", inflated: ");
                walk_chunk(inner, 0, chunk_size, chunk_inner, out);
                ++out.compressed_chunks;
            }
        } else if (r.op == kIndexData) {
            if (!chunk_seen) w.fail_at(r, "an index before any chunk");
            if (w.field<std::uint32_t>(r, "ver") != 1) w.fail_at(r, "index version is not 1");
            (void)w.field<std::uint32_t>(r, "conn");
            const std::uint64_t count = w.field<std::uint32_t>(r, "count");
            if (count * 12 != r.data_len) {
                w.fail_at(r, std::to_string(count) + " entries need " + std::to_string(count * 12) +
                                 " bytes, the data holds " + std::to_string(r.data_len));
            }
            const std::string entries = w.bytes(r.data_pos, r.data_len, size, "the index");
            for (std::uint64_t k = 0; k < count; ++k) {
                const auto offset =
                    little<std::uint32_t>(entries.substr(static_cast<std::size_t>(k * 12 + 8), 4));
                const bool walked = !chunk_compressed || params.walk_compressed;
                if (offset >= chunk_size || (walked && !chunk_inner.count(offset))) {
                    w.fail_at(r, "entry " + std::to_string(k) + " points to byte " +
                                     std::to_string(offset) +
                                     " of its chunk, where no message starts");
                }
            }
        } else if (r.op == kChunkInfo) {
            if (w.field<std::uint32_t>(r, "ver") != 1) w.fail_at(r, "chunk info version is not 1");
            const auto chunk_pos = w.field<std::uint64_t>(r, "chunk_pos");
            if (!chunk_starts.count(chunk_pos))
                w.fail_at(
                    r, "chunk_pos " + std::to_string(chunk_pos) + " is not the start of a chunk");
            const std::uint64_t count = w.field<std::uint32_t>(r, "count");
            if (count * 8 != r.data_len)
                w.fail_at(r, std::to_string(count) + " connection counts do not fill its data");
        } else if (r.op == kConnection) {
            (void)w.field<std::uint32_t>(r, "conn");
            if (!r.fields.count("topic")) w.fail_at(r, "no 'topic' field");
            if (r.data_len > kMaxConnectionBytes)
                w.fail_at(r, "a connection header of " + std::to_string(r.data_len) + " bytes");
            const auto header =
                w.fields(w.bytes(r.data_pos, r.data_len, size, "the connection header"), pos);
            for (const char* key : {"type", "md5sum"}) {
                if (!header.count(key))
                    w.fail_at(r, std::string("its connection header has no '") + key + "'");
            }
            ++out.connections;
        } else if (r.op != kMessageData) {
            w.fail_at(r, "unknown record kind");
        }
        pos = r.data_pos + r.data_len;
    }
    if (out.records == 0)
        throw io::FileError(path.string(), "not a ROS 1 bag (no bag header record)");
    if (index_pos == 0) return out;  // unindexed (a recording that was not closed): rosbag says so
    // rosbag reads conn_count connection records from index_pos, then chunk_count chunk infos.
    auto it = op_at.find(index_pos);
    if (it == op_at.end()) {
        throw io::FileError(path.string(),
                            "the bag header's index_pos " + std::to_string(index_pos) +
                                " is not the start of a record (damaged or cut short)");
    }
    for (std::uint64_t k = 0; k < std::uint64_t{conn_count} + chunk_count; ++k, ++it) {
        const std::uint8_t want = k < conn_count ? kConnection : kChunkInfo;
        if (it == op_at.end() || it->second != want) {
            throw io::FileError(path.string(),
                                "the index at byte " + std::to_string(index_pos) +
                                    " does not hold the " + std::to_string(conn_count) +
                                    " connections and " + std::to_string(chunk_count) +
                                    " chunk infos the bag header declares");
        }
    }
    return out;
}

}  // namespace makeway::rosio

// Every class of bad point-cloud input gives one FormatError/FileError that says what is wrong.
#include <gtest/gtest.h>

#include <fstream>

#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/pcd.hpp"
#include "io/point_cloud_io.hpp"
#include "io_test_util.hpp"

namespace makeway::io {
namespace {

struct BadCase {
    const char* name;
    CloudFormat format;
    std::string bytes;
    const char* expected;  ///< a substring of the message
};

std::string pcd_header(const std::string& data, const std::string& points = "2",
                       const std::string& fields = "x y z", const std::string& size = "4 4 4",
                       const std::string& type = "F F F") {
    return "VERSION 0.7\nFIELDS " + fields + "\nSIZE " + size + "\nTYPE " + type +
           "\nCOUNT 1 1 1\nWIDTH " + points + "\nHEIGHT 1\nPOINTS " + points + "\nDATA " + data +
           "\n";
}

std::string binary_pcd(std::size_t points) {
    return pcd_header("binary", std::to_string(points)) + std::string(points * 12, '\1');
}

std::string compressed_pcd(std::uint32_t compressed, std::uint32_t uncompressed,
                           std::size_t extra) {
    std::string s = pcd_header("binary_compressed");
    s.append(reinterpret_cast<const char*>(&compressed), 4);
    s.append(reinterpret_cast<const char*>(&uncompressed), 4);
    return s + std::string(extra, '\x55');
}

std::vector<BadCase> bad_cases() {
    const std::string ply_head =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
        "property float x\nproperty float y\nproperty float z\nend_header\n";
    return {
        {"pcd_wrong_magic", CloudFormat::kPcd, "hello world\n", "not a PCD file"},
        {"pcd_binary_garbage", CloudFormat::kPcd, std::string("\x89PNG\r\n\x1a\n", 8),
         "not a PCD file"},
        {"pcd_no_data_line", CloudFormat::kPcd, "VERSION 0.7\nFIELDS x y z\n",
         "before its DATA line"},
        {"pcd_truncated_binary", CloudFormat::kPcd,
         binary_pcd(2).substr(0, binary_pcd(2).size() - 5), "data size mismatch"},
        {"pcd_extra_binary", CloudFormat::kPcd, binary_pcd(2) + "xxxx", "data size mismatch"},
        {"pcd_huge_count", CloudFormat::kPcd, pcd_header("binary", "4000000000") + "abc",
         "data size mismatch"},
        {"pcd_huge_count_ascii", CloudFormat::kPcd, pcd_header("ascii", "4000000000") + "1 2 3\n",
         "truncated"},
        {"pcd_too_many_points", CloudFormat::kPcd, pcd_header("binary", "99999999999999"),
         "too large"},
        {"pcd_truncated_ascii", CloudFormat::kPcd, pcd_header("ascii") + "1 2 3\n4 5\n",
         "truncated"},
        {"pcd_extra_ascii", CloudFormat::kPcd, pcd_header("ascii") + "1 2 3\n4 5 6\n7\n",
         "more data"},
        {"pcd_bad_number", CloudFormat::kPcd, pcd_header("ascii") + "1 2 3\n4 five 6\n",
         "bad number"},
        {"pcd_points_mismatch", CloudFormat::kPcd,
         "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 3\nHEIGHT 1\nPOINTS 2\nDATA "
         "ascii\n",
         "WIDTH x HEIGHT"},
        {"pcd_unknown_type", CloudFormat::kPcd, pcd_header("ascii", "2", "x y z", "4 4 4", "F F Q"),
         "unknown TYPE"},
        {"pcd_bad_size", CloudFormat::kPcd, pcd_header("ascii", "2", "x y z", "4 4 3", "F F F"),
         "SIZE"},
        {"pcd_size_count_mismatch", CloudFormat::kPcd,
         pcd_header("ascii", "2", "x y z", "4 4", "F F F"), "2 entries for 3 FIELDS"},
        {"pcd_missing_z", CloudFormat::kPcd,
         "VERSION 0.7\nFIELDS x y\nSIZE 4 4\nTYPE F F\nWIDTH 1\nPOINTS 1\nDATA ascii\n1 2\n",
         "no 'z' field"},
        {"pcd_duplicate_field", CloudFormat::kPcd,
         "VERSION 0.7\nFIELDS x y z time t\nSIZE 4 4 4 4 4\nTYPE F F F F F\nWIDTH 1\nPOINTS 1\n"
         "DATA ascii\n1 2 3 4 5\n",
         "both give time"},
        {"pcd_unknown_data", CloudFormat::kPcd, pcd_header("zip"), "unknown DATA encoding"},
        {"pcd_unknown_header_line", CloudFormat::kPcd, "VERSION 0.7\nCOLOR red\n",
         "unknown header line"},
        {"pcd_negative_ring", CloudFormat::kPcd,
         "VERSION 0.7\nFIELDS x y z ring\nSIZE 4 4 4 4\nTYPE F F F I\nWIDTH 1\nPOINTS 1\nDATA "
         "ascii\n"
         "1 2 3 -4\n",
         "does not fit uint16"},
        {"pcd_compressed_short", CloudFormat::kPcd, pcd_header("binary_compressed") + "abc",
         "size words"},
        {"pcd_compressed_size_lie", CloudFormat::kPcd, compressed_pcd(100, 24, 10),
         "compressed size 100"},
        {"pcd_compressed_wrong_raw", CloudFormat::kPcd, compressed_pcd(10, 30, 10),
         "data size mismatch"},
        {"pcd_compressed_corrupt", CloudFormat::kPcd, compressed_pcd(10, 24, 10), "corrupt LZF"},
        {"ply_wrong_magic", CloudFormat::kPly, "plx\nformat ascii 1.0\n", "not a PLY file"},
        {"ply_no_end_header", CloudFormat::kPly, "ply\nformat ascii 1.0\nelement vertex 1\n",
         "before end_header"},
        {"ply_no_vertex", CloudFormat::kPly, "ply\nformat ascii 1.0\nelement face 0\nend_header\n",
         "no vertex element"},
        {"ply_no_format", CloudFormat::kPly, "ply\nelement vertex 0\nend_header\n",
         "no format line"},
        {"ply_truncated_binary", CloudFormat::kPly, ply_head + std::string(20, '\0'), "truncated"},
        {"ply_huge_count", CloudFormat::kPly,
         "ply\nformat binary_little_endian 1.0\nelement vertex 99999999999\nproperty float x\n"
         "property float y\nproperty float z\nend_header\n" +
             std::string(24, '\0'),
         "truncated"},
        {"ply_truncated_ascii", CloudFormat::kPly,
         "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
         "property float z\nend_header\n1 2 3\n4\n",
         "truncated"},
        {"ply_unknown_type", CloudFormat::kPly,
         "ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n",
         "unknown PLY property type"},
        {"ply_unknown_format", CloudFormat::kPly,
         "ply\nformat binary_middle_endian 1.0\nend_header\n", "unknown PLY format"},
        {"ply_missing_y", CloudFormat::kPly,
         "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float "
         "z\nend_header\n1 2\n",
         "no 'y' field"},
        {"kitti_odd_size", CloudFormat::kKittiBin, std::string(20, '\0'), "not a multiple of 16"},
        // The header says 2 vertices and 4 follow; `uchar x` declared over float data: both read as
        // garbage with exit 0 before.
        {"ply_more_ascii_than_declared", CloudFormat::kPly,
         "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty "
         "float z\nend_header\n"
         "1 2 3\n4 5 6\n7 8 9\n10 11 12\n",
         "data continues after the elements the header declares"},
        {"ply_uchar_over_float", CloudFormat::kPly,
         "ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty uchar x\nproperty float "
         "y\nproperty float z\n"
         "end_header\n" +
             std::string(24, '\0'),
         "bytes after the elements the header declares"},
        {"ply_non_ascii_name", CloudFormat::kPly,
         "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty "
         "float z\n"
         "property float \xff\xfe\nend_header\n1 2 3 4\n",
         "not printable ASCII"},
    };
}

TEST(CloudBadInput, EveryCaseThrowsFormatErrorSayingWhy) {
    for (const BadCase& c : bad_cases()) {
        try {
            parse_point_cloud(c.bytes, c.format);
            ADD_FAILURE() << c.name << ": accepted";
        } catch (const FormatError& e) {
            EXPECT_NE(std::string(e.what()).find(c.expected), std::string::npos)
                << c.name << ": got '" << e.what() << "'";
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << c.name;
        }
    }
}

TEST(CloudBadInput, FileLevelErrorsNameTheFile) {
    const auto dir = testing_util::fresh_dir("files");
    auto expect_error = [](const std::filesystem::path& p, const char* what) {
        try {
            read_point_cloud(p);
            ADD_FAILURE() << p << " accepted";
        } catch (const FileError& e) {
            const std::string msg = e.what();
            EXPECT_EQ(msg.rfind(p.string() + ": ", 0), 0u) << msg;
            EXPECT_NE(msg.find(what), std::string::npos) << msg;
        }
    };
    expect_error(dir / "missing.pcd", "no such file");
    expect_error(dir, "unknown point-cloud extension");
    std::filesystem::create_directories(dir / "folder.pcd");
    expect_error(dir / "folder.pcd", "is a folder");
    std::ofstream(dir / "empty.pcd").close();
    expect_error(dir / "empty.pcd", "empty file");
    std::ofstream(dir / "empty.bin").close();
    expect_error(dir / "empty.bin", "empty file");
    std::ofstream(dir / "bad.ply") << "ply\nformat ascii 1.0\n";
    expect_error(dir / "bad.ply", "before end_header");
}

TEST(AtomicWrite, FailureLeavesNoFileBehind) {
    const auto dir = testing_util::fresh_dir("atomic");
    std::ofstream(dir / "not_a_folder") << "x";
    EXPECT_THROW(write_file_atomic(dir / "not_a_folder" / "out.pcd", "data"), FileError);
    // An inconsistent cloud is refused before anything is written.
    PointCloud bad;
    bad.xyz.resize(3);
    bad.ring.resize(2);
    EXPECT_THROW(write_point_cloud(dir / "out.pcd", bad), FileError);
    EXPECT_FALSE(std::filesystem::exists(dir / "out.pcd"));
    // A successful write replaces the old file and leaves no temporary.
    write_file_atomic(dir / "a.txt", "old");
    write_file_atomic(dir / "a.txt", "new");
    EXPECT_EQ(read_file(dir / "a.txt"), "new");
    int entries = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++entries;
    EXPECT_EQ(entries, 2);  // not_a_folder, a.txt
}

}  // namespace
}  // namespace makeway::io

#include "io/pose_io.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <string>

#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/text_scan.hpp"
#include "makeway/common/angles.hpp"

namespace makeway::io {
namespace {

constexpr double kUnitTolerance = 1e-3;  // quaternion norm / rotation orthonormality
// A stamp is seconds since the epoch (1.7e9 now) or since the recording began; 1e10 s is 2286.
constexpr double kMaxStamp_s = 1e10;

template <std::size_t N>
std::array<double, N> parse_numbers(const std::vector<std::string_view>& words,
                                    std::size_t line_no) {
    const std::string where = "line " + std::to_string(line_no) + ": ";
    if (words.size() != N) {
        throw FormatError(where + "expected " + std::to_string(N) + " numbers, found " +
                          std::to_string(words.size()));
    }
    std::array<double, N> v{};
    for (std::size_t i = 0; i < N; ++i) {
        const auto w = words[i];
        auto [ptr, ec] = std::from_chars(w.data(), w.data() + w.size(), v[i]);
        if (ec != std::errc() || ptr != w.data() + w.size()) {
            throw FormatError(where + "bad number '" + std::string(w.substr(0, 40)) + "'");
        }
        if (!std::isfinite(v[i])) throw FormatError(where + "value is NaN or infinite");
    }
    return v;
}

// The shortest round-trip form: files keep every bit, messages say 1e+300, not 300 digits.
std::string shortest(double v) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof(buf), v);
    return std::string(buf, r.ptr);
}

template <typename Fn>
void for_each_data_line(std::string_view text, Fn&& fn) {
    std::size_t pos = 0;
    std::size_t line_no = 0;
    while (const auto line = next_line(text, pos)) {
        ++line_no;
        const auto words = split_words(*line);
        if (words.empty() || words[0].front() == '#') continue;
        fn(words, line_no);
    }
}

template <typename T, typename Parse>
T read_with(const std::filesystem::path& path, Parse parse) {
    const std::string text = read_file(path);
    try {
        return parse(text);
    } catch (const FormatError& e) {
        throw FileError(path.string(), e.what());
    }
}

}  // namespace

std::vector<StampedPose> parse_tum(std::string_view text) {
    std::vector<StampedPose> poses;
    for_each_data_line(text, [&](const auto& words, std::size_t line_no) {
        const auto v = parse_numbers<8>(words, line_no);
        Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
        if (std::abs(q.norm() - 1.0) > kUnitTolerance) {
            throw FormatError("line " + std::to_string(line_no) + ": quaternion norm " +
                              std::to_string(q.norm()) + " is not 1");
        }
        if (!poses.empty() && v[0] < poses.back().stamp_s) {
            throw FormatError("line " + std::to_string(line_no) + ": timestamp goes backwards");
        }
        if (!poses.empty() && v[0] == poses.back().stamp_s) {
            throw FormatError("line " + std::to_string(line_no) + ": timestamp " + shortest(v[0]) +
                              " repeats the line before's");
        }
        if (v[0] < 0.0 || v[0] > kMaxStamp_s) {
            throw FormatError(
                "line " + std::to_string(line_no) + ": timestamp " + shortest(v[0]) +
                " is not seconds in [0, 1e10] (since the epoch, or since the recording began)");
        }
        if (Eigen::Vector3d(v[1], v[2], v[3]).norm() > kMaxPosition_m) {
            throw FormatError("line " + std::to_string(line_no) + ": position " +
                              shortest(Eigen::Vector3d(v[1], v[2], v[3]).norm()) +
                              " m from the origin (more than 100 km)");
        }
        StampedPose p;
        p.stamp_s = v[0];
        p.T_world_sensor.linear() = q.normalized().toRotationMatrix();
        p.T_world_sensor.translation() = Eigen::Vector3d(v[1], v[2], v[3]);
        poses.push_back(p);
    });
    if (poses.empty()) throw FormatError("no poses");
    return poses;
}

std::vector<Isometry3> parse_kitti_poses(std::string_view text) {
    std::vector<Isometry3> poses;
    for_each_data_line(text, [&](const auto& words, std::size_t line_no) {
        const auto v = parse_numbers<12>(words, line_no);
        Isometry3 T = Isometry3::Identity();
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 4; ++c) T.matrix()(r, c) = v[static_cast<std::size_t>(4 * r + c)];
        }
        const Eigen::Matrix3d R = T.linear();
        if ((R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() >
                kUnitTolerance ||
            R.determinant() < 0.0) {
            throw FormatError("line " + std::to_string(line_no) + ": not a rotation matrix");
        }
        poses.push_back(orthonormalized(T));
    });
    if (poses.empty()) throw FormatError("no poses");
    return poses;
}

std::vector<StampedPose> read_tum(const std::filesystem::path& path) {
    return read_with<std::vector<StampedPose>>(path, parse_tum);
}

std::vector<Isometry3> read_kitti_poses(const std::filesystem::path& path) {
    return read_with<std::vector<Isometry3>>(path, parse_kitti_poses);
}

void write_tum(const std::filesystem::path& path, const std::vector<StampedPose>& poses) {
    std::string out = "# timestamp tx ty tz qx qy qz qw\n";
    for (const StampedPose& p : poses) {
        const Eigen::Quaterniond q(p.T_world_sensor.linear());
        const Eigen::Vector3d t = p.T_world_sensor.translation();
        for (double v : {p.stamp_s, t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w()}) {
            out += shortest(v);
            out += ' ';
        }
        out.back() = '\n';
    }
    write_file_atomic(path, out);
}

void write_kitti_poses(const std::filesystem::path& path, const std::vector<Isometry3>& poses) {
    std::string out;
    for (const Isometry3& T : poses) {
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 4; ++c) {
                out += shortest(T.matrix()(r, c));
                out += ' ';
            }
        }
        out.back() = '\n';
    }
    write_file_atomic(path, out);
}

std::string extrinsics_problem(const std::vector<double>& v) {
    if (v.size() != 6 ||
        !std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); }))
        return "expected 6 finite numbers";
    if (Eigen::Vector3d(v[0], v[1], v[2]).norm() > 10.0)
        return "the sensor lies " + shortest(Eigen::Vector3d(v[0], v[1], v[2]).norm()) +
               " m from the base (at most 10 m)";
    for (std::size_t i = 3; i < 6; ++i) {
        if (std::abs(v[i]) > 2 * kPi)
            return "angle " + shortest(v[i]) + " is beyond +-2 pi (radians, not degrees)";
    }
    return "";
}

std::string start_problem(const std::vector<double>& v) {
    if (v.size() != 3 ||
        !std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); }))
        return "expected 3 finite numbers";
    if (Eigen::Vector2d(v[0], v[1]).norm() > kMaxPosition_m) {
        return "the start lies " + shortest(Eigen::Vector2d(v[0], v[1]).norm()) +
               " m from the origin (at most 100 km)";
    }
    if (std::abs(v[2]) > 2 * kPi)
        return "yaw " + shortest(v[2]) + " is beyond +-2 pi (radians, not degrees)";
    return "";
}

}  // namespace makeway::io

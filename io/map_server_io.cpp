#include "io/map_server_io.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>

#include "io/config_reader.hpp"
#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/text_scan.hpp"

namespace makeway::io {
namespace {

constexpr unsigned char kUnknownPixel = 205;

// The next whitespace-separated header token, skipping '#' comments.
std::string_view pgm_token(std::string_view bytes, std::size_t& pos) {
    while (pos < bytes.size()) {
        if (bytes[pos] == '#') {
            while (pos < bytes.size() && bytes[pos] != '\n') ++pos;
        } else if (is_space(bytes[pos])) {
            ++pos;
        } else {
            break;
        }
    }
    const std::size_t start = pos;
    while (pos < bytes.size() && !is_space(bytes[pos]) && bytes[pos] != '#') ++pos;
    return bytes.substr(start, pos - start);
}

}  // namespace

PgmImage parse_pgm(std::string_view bytes) {
    std::size_t pos = 0;
    if (pgm_token(bytes, pos) != "P5") throw FormatError("not a binary PGM (P5) image");
    const auto w = parse_count(pgm_token(bytes, pos));
    const auto h = parse_count(pgm_token(bytes, pos));
    const auto maxval = parse_count(pgm_token(bytes, pos));
    if (!w || !h || *w == 0 || *h == 0 || *w > 100000 || *h > 100000)
        throw FormatError("bad PGM size");
    if (!maxval || *maxval != 255) throw FormatError("only 8-bit PGM (maxval 255) is supported");
    ++pos;  // the single whitespace after maxval
    const std::size_t n = static_cast<std::size_t>(*w) * static_cast<std::size_t>(*h);
    if (pos > bytes.size() || bytes.size() - pos != n) {
        throw FormatError("PGM data size mismatch: " + std::to_string(*w) + " x " +
                          std::to_string(*h) + " needs " + std::to_string(n) + " bytes, found " +
                          std::to_string(pos > bytes.size() ? 0 : bytes.size() - pos));
    }
    return {static_cast<int>(*w), static_cast<int>(*h), std::string(bytes.substr(pos))};
}

std::string serialize_pgm(const PgmImage& image) {
    return "P5\n# makeway costmap\n" + std::to_string(image.width) + " " +
           std::to_string(image.height) + "\n255\n" + image.pixels;
}

void write_map_server(const std::filesystem::path& yaml_path, const Costmap& m) {
    PgmImage img{m.width, m.height, std::string(m.cost.size(), '\0')};
    for (int y = 0; y < m.height; ++y) {
        for (int x = 0; x < m.width; ++x) {
            const std::uint8_t c = m.at(x, y);
            const unsigned char p =
                c == cost::kUnknown
                    ? kUnknownPixel
                    : static_cast<unsigned char>(255 - std::lround(c * 255.0 / 254.0));
            img.pixels[static_cast<std::size_t>(m.height - 1 - y) * m.width + x] =
                static_cast<char>(p);  // top row first
        }
    }
    auto pgm_path = yaml_path;
    pgm_path.replace_extension(".pgm");
    write_file_atomic(pgm_path, serialize_pgm(img));
    YAML::Emitter out;
    out << YAML::BeginMap << YAML::Key << "image" << YAML::Value << pgm_path.filename().string()
        << YAML::Key << "mode" << YAML::Value << "scale" << YAML::Key << "resolution" << YAML::Value
        << m.resolution_m << YAML::Key << "origin" << YAML::Value << YAML::Flow << YAML::BeginSeq
        << m.origin_m.x() << m.origin_m.y() << 0.0 << YAML::EndSeq << YAML::Key << "negate"
        << YAML::Value << 0 << YAML::Key << "occupied_thresh" << YAML::Value << 0.65 << YAML::Key
        << "free_thresh" << YAML::Value << 0.196
        << YAML::EndMap;  // ROS defaults: 205 reads as unknown
    write_file_atomic(yaml_path, std::string(out.c_str()) + "\n");
}

Costmap read_map_server(const std::filesystem::path& yaml_path) {
    const std::string text = read_file(yaml_path);
    std::vector<std::string> problems;
    std::string image, mode = "trinary";
    double resolution = 0.05, occupied = 0.65, free = 0.25;
    int negate = 0;
    std::vector<double> origin;
    YAML::Node root;
    try {
        root = load_yaml(text);
    } catch (const FormatError& e) {
        throw FileError(yaml_path.string(), e.what());
    }
    {
        YamlSection s(root, "map", problems);
        s.read("image", image);
        s.read("mode", mode);
        s.read("resolution", resolution);
        s.read("negate", negate);
        s.read("occupied_thresh", occupied);
        s.read("free_thresh", free);
        const YAML::Node o = s.take("origin");
        try {
            if (o) origin = o.as<std::vector<double>>();
        } catch (const YAML::Exception&) {
        }
        if (origin.size() != 3) s.problem("origin must be [x, y, yaw]");
        if (image.empty()) s.problem("image is missing");
        // map_server's keys: mode trinary/scale/raw, negate 0/1; cells of 1 mm to 100 m (a finer
        // map of a room is millions of cells the planner would crawl through).
        if (!(resolution >= 0.001 && resolution < 100.0))
            s.problem("resolution must be in [0.001, 100)");
        if (mode != "trinary" && mode != "scale" && mode != "raw")
            s.problem("mode must be trinary, scale or raw (got '" + mode + "')");
        if (negate != 0 && negate != 1) s.problem("negate must be 0 or 1");
        if (!(free >= 0.0 && free < occupied && occupied <= 1.0))
            s.problem("need 0 <= free_thresh < occupied_thresh <= 1");
        s.finish();
    }
    if (!problems.empty()) throw FileError(yaml_path.string(), join_problems(problems));
    const std::filesystem::path image_path = yaml_path.parent_path() / image;
    PgmImage img;
    try {
        img = parse_pgm(read_file(image_path));
    } catch (const FormatError& e) {
        throw FileError(image_path.string(), e.what());
    }
    Costmap m({origin[0], origin[1]}, resolution, img.width, img.height);
    for (int y = 0; y < img.height; ++y) {
        for (int x = 0; x < img.width; ++x) {
            const auto p = static_cast<unsigned char>(
                img.pixels[static_cast<std::size_t>(img.height - 1 - y) * img.width + x]);
            const double occ = negate ? p / 255.0 : (255.0 - p) / 255.0;
            m.at(x, y) = occ > occupied ? cost::kLethal : occ < free ? cost::kFree : cost::kUnknown;
        }
    }
    return m;
}

}  // namespace makeway::io

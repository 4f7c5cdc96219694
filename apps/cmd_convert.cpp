#include "apps/command.hpp"
#include "io/error.hpp"
#include "io/point_cloud_io.hpp"

namespace makeway::apps {

struct ConvertOptions {
    std::string input;
    std::string output;
    std::string pcd_encoding = "binary";
    std::string ply_encoding = "binary";
    std::string non_finite = "reject";
};

namespace {

io::NonFinitePolicy parse_policy(const std::string& name) {
    if (name == "keep") return io::NonFinitePolicy::kKeep;
    if (name == "drop") return io::NonFinitePolicy::kDrop;
    return io::NonFinitePolicy::kReject;
}

std::string join(const std::vector<std::string>& words) {
    std::string out;
    for (const auto& w : words) out += (out.empty() ? "" : ", ") + w;
    return out;
}

}  // namespace

int run_convert(const ConvertOptions& options) {
    if (!io::cloud_format_from_path(options.output)) {
        throw io::FileError(options.output,
                            "unknown point-cloud extension (expected .pcd, .ply or .bin)");
    }
    const io::CloudFile file =
        io::read_point_cloud(options.input, {.non_finite = parse_policy(options.non_finite)});
    if (file.cloud.size() == 0) {  // every point dropped: no file that `info` would then reject
        throw io::FileError(options.input, "no finite points left to convert");
    }
    if (!file.info.ignored_fields.empty()) {
        io::print_warning(options.input + ": fields not kept (makeway has no channel for them): " +
                          join(file.info.ignored_fields));
    }
    io::CloudWriteOptions write;
    write.pcd = *io::parse_pcd_encoding(options.pcd_encoding);
    write.ply = *io::parse_ply_encoding(options.ply_encoding);
    const auto dropped = io::write_point_cloud(options.output, file.cloud, write);
    if (!dropped.empty()) {
        io::print_warning(options.output + ": the format cannot hold " + join(dropped) +
                          "; dropped");
    }
    return 0;
}

// The subcommands of this file, as --help lists them.
namespace {

void declare_convert(CommandSpec& c, ConvertOptions& o) {
    c.option("IN", o.input, "Input cloud (.pcd, .ply, .bin)").required();
    c.option("OUT", o.output, "Output cloud (.pcd, .ply, .bin); written atomically").required();
    c.option("--pcd-encoding", o.pcd_encoding, "PCD DATA encoding")
        .choices({"ascii", "binary", "binary_compressed"})
        .show_default();
    c.option("--ply-encoding", o.ply_encoding, "PLY encoding (binary = little endian)")
        .choices({"ascii", "binary"})
        .show_default();
    c.option("--non-finite", o.non_finite,
             "Points with NaN/inf coordinates: reject the file, keep them, or drop them")
        .choices({"reject", "keep", "drop"})
        .show_default();
}
const Registration<ConvertOptions> kConvert{"convert", Group::kPointClouds,
                                            "Convert a point cloud between PCD, PLY and KITTI .bin "
                                            "by file extension, keeping every field both hold",
                                            declare_convert, run_convert};

}  // namespace

}  // namespace makeway::apps

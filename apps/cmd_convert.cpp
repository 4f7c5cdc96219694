#include "apps/commands.hpp"
#include "io/error.hpp"
#include "io/point_cloud_io.hpp"

namespace makeway::apps {
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

}  // namespace makeway::apps

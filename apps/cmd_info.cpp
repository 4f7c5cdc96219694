#include <iostream>

#include "apps/command.hpp"
#include "io/json_io.hpp"
#include "io/point_cloud_io.hpp"

namespace makeway::apps {

struct InfoOptions {
    std::string path;
};

int run_info(const InfoOptions& options) {
    const io::CloudFile file =
        io::read_point_cloud(options.path, {.non_finite = io::NonFinitePolicy::kKeep});
    io::Json j;
    j["file"] = options.path;
    j["format"] = file.info.format;
    j["encoding"] = file.info.encoding;
    j["points"] = file.cloud.size();
    j["fields"] = file.info.fields;
    j["ignored_fields"] = file.info.ignored_fields;
    j["bounds_m"] = io::to_json(compute_bounds(file.cloud));
    j["nan_count"] = file.cloud.count_non_finite();
    std::cout << io::dump_json(j) << "\n";
    return 0;
}

// The subcommands of this file, as --help lists them.
namespace {

void declare_info(CommandSpec& c, InfoOptions& o) {
    c.option("FILE", o.path, "Point cloud (.pcd, .ply, or KITTI .bin)").required();
}
const Registration<InfoOptions> kInfo{"info", Group::kPointClouds,
                                      "Print one JSON object describing a point-cloud file: "
                                      "format, encoding, point count, fields, bounds [m], "
                                      "count of points with NaN/inf coordinates",
                                      declare_info, run_info};

}  // namespace

}  // namespace makeway::apps

#include <iostream>

#include "apps/commands.hpp"
#include "io/json_io.hpp"
#include "io/point_cloud_io.hpp"

namespace makeway::apps {

void print_error(const std::string& message) { std::cerr << "makeway: " << message << "\n"; }

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

}  // namespace makeway::apps

#pragma once
// The result of parsing a point-cloud file: the cloud and what the file declared.
#include <string>
#include <vector>

#include "makeway/common/point_cloud.hpp"

namespace makeway::io {

struct CloudFileInfo {
    std::string format;                       ///< "pcd", "ply" or "kitti_bin"
    std::string encoding;                     ///< "ascii", "binary", "binary_compressed", ...
    std::vector<std::string> fields;          ///< every field of the file, in file order
    std::vector<std::string> ignored_fields;  ///< fields makeway has no channel for
};

struct CloudFile {
    PointCloud cloud;
    CloudFileInfo info;
};

}  // namespace makeway::io

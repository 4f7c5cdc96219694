#pragma once
// What `dataset` and `eval-detection` (cmd_detector.cpp, cmd_eval_detection.cpp) both read from
// the command line: the simulated LiDAR's beam patterns and the user's real furniture models.
#include <string>
#include <vector>

#include "io/error.hpp"
#include "io/furniture_folder.hpp"
#include "makeway/eval/detection_dataset.hpp"
#include "makeway/sim/lidar.hpp"

namespace makeway::apps {

/// The names --beam-pattern admits, in sim::beam_patterns_by_name()'s order.
inline std::vector<std::string> beam_pattern_names() {
    return names_in(sim::beam_patterns_by_name());
}

/// The user's furniture folder (empty: none) read and split as eval::split_furniture does: every
/// `holdout_every`-th model of each class by name is held out of training.
inline eval::FurnitureSplit read_furniture_split(const std::string& folder, int holdout_every) {
    std::vector<eval::UserFurniture> all;
    if (!folder.empty()) {
        for (io::FurnitureMesh& m : io::read_furniture_folder(folder, io::print_warning))
            all.push_back({m.name, m.cls, std::move(m.mesh_object)});
    }
    return eval::split_furniture(std::move(all), holdout_every);
}

}  // namespace makeway::apps

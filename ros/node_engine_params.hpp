#pragma once
// The online system's parameters as the node builds them from its settings: the same function as
// `makeway run` and the benchmark (io::online_system_params), so the three cannot drift. Apart from
// node_engine.hpp because the node's main is C++17 and this header's types are not.
#include "makeway/pipeline/system_params.hpp"
#include "ros/node_engine.hpp"

namespace makeway::rosio {

/// The configuration file (defaults when none) with the robot applied, and the measured extrinsics.
/// Throws io::FileError naming a bad configuration.
pipeline::SystemParams node_system_params(const NodeSettings& settings);

}  // namespace makeway::rosio

#pragma once
// The ROS node's engine: the online system (MappingSystem) on a worker thread behind a queue, so
// that the sweep callback only converts and enqueues and a slow keyframe never drops a sweep. It
// names no ROS type and is C++17-clean: the node's main (ros/makeway_node.cpp) is C++17 because
// ROS 1's message headers are.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "makeway/common/costmap.hpp"
#include "makeway/common/object_estimate.hpp"
#include "makeway/common/transforms.hpp"
#include "makeway/costmap/affordance.hpp"
#include "ros/bag_io.hpp"

namespace makeway::rosio {

struct NodeSettings {
    std::string config;  ///< YAML, the program's format (empty: built-in defaults)
    std::string model;   ///< detector weights (empty: models/detector.pt)
    std::string cad;     ///< CAD folder (empty: verification skipped)
    std::string map;     ///< map_server YAML (empty: a free square around the start)
    double costmap_size_m = 40.0;
    std::optional<Pose2> start;     ///< the base at the first sweep (default: the first odometry pose, else 0 0 0)
    double odometry_wait_s = 0.2;   ///< how long a sweep waits for odometry covering its end
    std::size_t max_queue = 600;    ///< sweeps waiting beyond this are dropped (and counted)
};

/// What one sweep produced, carrying the stamp of the data it used (the sweep's end).
struct NodeOutput {
    double stamp_s = 0.0;
    Pose2 pose;                          ///< the base, estimated
    Isometry3 T_world_sensor = Isometry3::Identity();
    bool keyframe = false;
    std::vector<ObjectEstimate> objects;  ///< the object map
    const Costmap* costmap = nullptr;     ///< valid during the callback
    std::string object_map_json;          ///< keyframes: the object map as `makeway run` writes it
    double per_sweep_ms = 0.0, keyframe_ms = 0.0, queue_wait_ms = 0.0;
};

struct NodeStats {
    std::size_t received = 0, processed = 0, dropped = 0, keyframes = 0, max_queue = 0;
};

class NodeEngine {
public:
    using Publish = std::function<void(const NodeOutput&)>;
    /// Loads everything (throws io::FileError naming a bad file) and starts the worker, which
    /// calls `publish` after every sweep.
    NodeEngine(const NodeSettings& settings, Publish publish);
    ~NodeEngine();  ///< finishes the queued sweeps, then stops
    NodeEngine(const NodeEngine&) = delete;
    NodeEngine& operator=(const NodeEngine&) = delete;

    /// From the callbacks' threads; return at once.
    void push_sweep(CloudSweep sweep);
    void push_odometry(const StampedPose2& pose);
    /// Blocks until every queued sweep is processed.
    void drain();

    NodeStats stats() const;
    const costmap::AffordanceParams& zones() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace makeway::rosio

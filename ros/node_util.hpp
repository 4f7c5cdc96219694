#pragma once
// What both ROS nodes (makeway_node, makeway_sim_node) need around roscpp: private parameters with
// defaults, and a stop flag set by SIGINT/SIGTERM so that each can send its last messages (a
// zero command, a report) before it shuts ROS down. Includes ROS headers: C++17.
#include <ros/ros.h>

#include <atomic>
#include <csignal>
#include <string>

namespace makeway::rosio {

/// The parameter `name` of `nh`, else `fallback`.
template <typename T>
T param(ros::NodeHandle& nh, const std::string& name, const T& fallback) {
    T value;
    return nh.param<T>(name, value, fallback) ? value : fallback;
}

/// Set by SIGINT or SIGTERM once install_stop_signals() ran (ros::init with NoSigintHandler).
inline std::atomic<bool>& stop_requested() {
    static std::atomic<bool> flag{false};
    return flag;
}

inline void install_stop_signals() {
    stop_requested() = false;  // initialised here, not first in a handler
    static const auto handler = [](int) { stop_requested() = true; };
    std::signal(SIGINT, handler);
    std::signal(SIGTERM, handler);
}

}  // namespace makeway::rosio

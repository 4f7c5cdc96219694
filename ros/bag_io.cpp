#include "ros/bag_io.hpp"

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <std_msgs/String.h>

#include <algorithm>
#include <map>

#include "io/error.hpp"
#include "ros/msg_conversions.hpp"

namespace makeway::rosio {
namespace {

constexpr const char* kCloudType = "sensor_msgs/PointCloud2";
constexpr const char* kOdometryType = "nav_msgs/Odometry";

// Topic -> message type, over the whole bag.
std::map<std::string, std::string> topic_types(rosbag::Bag& bag) {
    std::map<std::string, std::string> out;
    rosbag::View all(bag);
    for (const rosbag::ConnectionInfo* c : all.getConnections()) out[c->topic] = c->datatype;
    return out;
}

std::string topics_of_type(const std::map<std::string, std::string>& types, const std::string& type) {
    std::string list;
    for (const auto& [topic, t] : types) {
        if (t == type) list += (list.empty() ? "" : ", ") + topic;
    }
    return list.empty() ? "none" : list;
}

void check_topic(const std::filesystem::path& path, const std::map<std::string, std::string>& types, const std::string& topic,
                 const std::string& type, const std::string& option) {
    const auto it = types.find(topic);
    if (it == types.end()) {
        throw io::FileError(path.string(), "no topic " + topic + " (" + type + " topics in the bag: " +
                                               topics_of_type(types, type) + "; choose one with " + option + ")");
    }
    if (it->second != type) throw io::FileError(path.string(), "topic " + topic + " holds " + it->second + ", not " + type);
}

}  // namespace

struct BagReader::Impl {
    std::filesystem::path path;
    std::string cloud_topic;
    rosbag::Bag bag;
    std::unique_ptr<rosbag::View> view;
    rosbag::View::iterator it;
    std::size_t sweeps = 0, read = 0;
    std::vector<StampedPose2> odometry;
};

BagReader::BagReader(const std::filesystem::path& path, const BagTopics& topics, bool require_odometry)
    : impl_(std::make_unique<Impl>()) {
    impl_->path = path;
    impl_->cloud_topic = topics.cloud;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) throw io::FileError(path.string(), "no such bag file");
    try {
        impl_->bag.open(path.string(), rosbag::bagmode::Read);
        const auto types = topic_types(impl_->bag);
        check_topic(path, types, topics.cloud, kCloudType, "--cloud-topic");
        if (require_odometry || types.count(topics.odometry)) check_topic(path, types, topics.odometry, kOdometryType, "--odom-topic");
        if (types.count(topics.odometry)) {
            rosbag::View odom(impl_->bag, rosbag::TopicQuery(topics.odometry));
            for (const rosbag::MessageInstance& m : odom) {
                const auto msg = m.instantiate<nav_msgs::Odometry>();
                if (!msg) continue;
                const double stamp = msg->header.stamp.isZero() ? m.getTime().toSec() : msg->header.stamp.toSec();
                impl_->odometry.push_back({stamp, pose_from_odometry(*msg)});
            }
            std::stable_sort(impl_->odometry.begin(), impl_->odometry.end(),
                             [](const StampedPose2& a, const StampedPose2& b) { return a.stamp_s < b.stamp_s; });
        }
        impl_->view = std::make_unique<rosbag::View>(impl_->bag, rosbag::TopicQuery(topics.cloud));
        impl_->sweeps = impl_->view->size();
        impl_->it = impl_->view->begin();
    } catch (const rosbag::BagException& e) {
        throw io::FileError(path.string(), std::string("not a readable ROS 1 bag: ") + e.what());
    }
}

BagReader::~BagReader() = default;

std::size_t BagReader::sweeps() const { return impl_->sweeps; }
const std::vector<StampedPose2>& BagReader::odometry() const { return impl_->odometry; }

std::optional<CloudSweep> BagReader::next() {
    try {
        for (; impl_->it != impl_->view->end();) {
            const rosbag::MessageInstance& m = *impl_->it;
            const std::size_t k = impl_->read++;
            const auto msg = m.instantiate<sensor_msgs::PointCloud2>();
            ++impl_->it;
            if (!msg) continue;
            try {
                CloudSweep s = from_point_cloud2(*msg);
                if (msg->header.stamp.isZero()) s.stamp_s += m.getTime().toSec();
                return s;
            } catch (const io::FormatError& e) {
                throw io::FileError(impl_->path.string(), impl_->cloud_topic + " message " + std::to_string(k) + ": " + e.what());
            }
        }
    } catch (const rosbag::BagException& e) {
        throw io::FileError(impl_->path.string(), std::string("unreadable: ") + e.what());
    }
    return std::nullopt;
}

std::map<std::string, BagTopic> bag_topics(const std::filesystem::path& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) throw io::FileError(path.string(), "no such bag file");
    std::map<std::string, BagTopic> out;
    try {
        rosbag::Bag bag(path.string(), rosbag::bagmode::Read);
        for (const auto& [topic, type] : topic_types(bag)) {
            rosbag::View view(bag, rosbag::TopicQuery(topic));
            out[topic] = {type, view.size()};
        }
    } catch (const rosbag::BagException& e) {
        throw io::FileError(path.string(), std::string("not a readable ROS 1 bag: ") + e.what());
    }
    return out;
}

struct BagWriter::Impl {
    std::filesystem::path path, active;
    rosbag::Bag bag;
    bool closed = false;

    template <typename M>
    void write(const std::string& topic, double stamp_s, const M& msg) {
        try {
            bag.write(topic, to_ros_time(stamp_s), msg);
        } catch (const rosbag::BagException& e) {
            throw io::FileError(path.string(), std::string("cannot write: ") + e.what());
        }
    }
};

BagWriter::BagWriter(const std::filesystem::path& path) : impl_(std::make_unique<Impl>()) {
    impl_->path = path;
    impl_->active = path.string() + ".active";
    try {
        impl_->bag.open(impl_->active.string(), rosbag::bagmode::Write);
        impl_->bag.setCompression(rosbag::compression::LZ4);
    } catch (const rosbag::BagException& e) {
        throw io::FileError(path.string(), std::string("cannot write: ") + e.what());
    }
}

BagWriter::~BagWriter() {
    if (impl_->closed) return;
    try {
        impl_->bag.close();
    } catch (...) {
    }
    std::error_code ec;
    std::filesystem::remove(impl_->active, ec);
}

void BagWriter::write_cloud(const std::string& topic, const PointCloud& cloud, double stamp_s, const std::string& frame_id) {
    impl_->write(topic, stamp_s, to_point_cloud2(cloud, stamp_s, frame_id));
}

void BagWriter::write_odometry(const std::string& topic, const Pose2& pose, double v_mps, double w_radps, double stamp_s,
                               const std::string& frame_id, const std::string& child_frame_id) {
    impl_->write(topic, stamp_s, to_odometry(pose, v_mps, w_radps, stamp_s, frame_id, child_frame_id));
}

void BagWriter::write_costmap(const std::string& topic, const Costmap& costmap, double stamp_s, const std::string& frame_id) {
    impl_->write(topic, stamp_s, to_occupancy_grid(costmap, stamp_s, frame_id));
}

void BagWriter::write_markers(const std::string& topic, const std::vector<ObjectEstimate>& objects,
                              const costmap::AffordanceParams& zones, double stamp_s, const std::string& frame_id) {
    impl_->write(topic, stamp_s, to_markers(objects, zones, stamp_s, frame_id));
}

void BagWriter::write_tf(const Isometry3& T_parent_child, double stamp_s, const std::string& parent, const std::string& child,
                         bool is_static) {
    impl_->write(is_static ? "/tf_static" : "/tf", stamp_s, to_tf(T_parent_child, stamp_s, parent, child));
}

void BagWriter::write_text(const std::string& topic, const std::string& text, double stamp_s) {
    std_msgs::String msg;
    msg.data = text;
    impl_->write(topic, stamp_s, msg);
}

void BagWriter::close() {
    if (impl_->closed) return;
    try {
        impl_->bag.close();
    } catch (const rosbag::BagException& e) {
        throw io::FileError(impl_->path.string(), std::string("cannot write: ") + e.what());
    }
    std::error_code ec;
    std::filesystem::rename(impl_->active, impl_->path, ec);
    if (ec) throw io::FileError(impl_->path.string(), "cannot write: " + ec.message());
    impl_->closed = true;
}

}  // namespace makeway::rosio

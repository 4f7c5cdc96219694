#include "ros/bag_io.hpp"

#include <console_bridge/console.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <std_msgs/String.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <map>
#include <mutex>

#include "io/error.hpp"
#include "ros/bag_check.hpp"
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

std::string topics_of_type(const std::map<std::string, std::string>& types,
                           const std::string& type) {
    std::string list;
    for (const auto& [topic, t] : types) {
        if (t == type) list += (list.empty() ? "" : ", ") + topic;
    }
    return list.empty() ? "none" : list;
}

void check_topic(const std::filesystem::path& path, const std::map<std::string, std::string>& types,
                 const std::string& topic, const std::string& type, const std::string& option) {
    const auto it = types.find(topic);
    if (it == types.end()) {
        throw io::FileError(path.string(),
                            "no topic " + topic + " (" + type + " topics in the bag: " +
                                topics_of_type(types, type) + "; choose one with " + option + ")");
    }
    if (it->second != type)
        throw io::FileError(path.string(),
                            "topic " + topic + " holds " + it->second + ", not " + type);
}

// rosbag and ros::Header report through console_bridge, straight to the terminal ("Received an
// invalid TCPROS header ...", one "Index entry ... contains invalid time" per message): that text
// is kept here instead, and a reader turns it into one warning of its own.
class CapturedConsole : public console_bridge::OutputHandler {
  public:
    void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
        if (level < console_bridge::CONSOLE_BRIDGE_LOG_WARN) return;
        const std::lock_guard<std::mutex> lock(mutex_);
        if (count_++ == 0) first_ = text;
    }
    // What was logged since the last call: the first message and how many there were.
    std::pair<std::string, std::size_t> take() {
        const std::lock_guard<std::mutex> lock(mutex_);
        std::pair<std::string, std::size_t> out{first_, count_};
        first_.clear();
        count_ = 0;
        return out;
    }

  private:
    std::mutex mutex_;
    std::string first_;
    std::size_t count_ = 0;
};

CapturedConsole& captured_console() {
    static CapturedConsole* handler = [] {
        auto* h =
            new CapturedConsole;  // lives as long as the process: console_bridge keeps the pointer
        console_bridge::useOutputHandler(h);
        return h;
    }();
    return *handler;
}

// One warning for what rosbag printed while `path` was read, if anything.
void warn_captured(const std::filesystem::path& path) {
    const auto [first, count] = captured_console().take();
    if (count == 0) return;
    std::string text = first;
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
    io::print_warning(path.string() + ": rosbag: " + text +
                      (count > 1 ? " (" + std::to_string(count) + " such messages)" : ""));
}

void check_bytes(const std::vector<std::uint8_t>& b, const sensor_msgs::PointCloud2*) {
    check_cloud_message(b.data(), b.size());
}
void check_bytes(const std::vector<std::uint8_t>& b, const nav_msgs::Odometry*) {
    check_odometry_message(b.data(), b.size());
}

// The message, or io::FormatError saying why it is not one.
template <typename M>
M deserialise(const rosbag::MessageInstance& m) {
    const std::string want = ros::message_traits::md5sum<M>();
    if (m.getMD5Sum() != want && m.getMD5Sum() != "*") {
        throw io::FormatError("its md5sum " + m.getMD5Sum() + " is not " +
                              ros::message_traits::datatype<M>() + "'s " + want +
                              " (another definition of the message)");
    }
    std::vector<std::uint8_t> bytes(m.size());
    ros::serialization::OStream out(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
    m.write(out);
    check_bytes(bytes, static_cast<const M*>(nullptr));  // before ROS's deserialiser trusts them
    M msg;
    ros::serialization::IStream in(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
    ros::serialization::deserialize(in, msg);
    return msg;
}

}  // namespace

std::string seconds_text(double t_s) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.3f", t_s);
    return text;
}

std::string sweep_span_problem(double span_s) {
    if (span_s <= kMaxSweepSpan_s) return "";
    char bound[16];
    std::snprintf(bound, sizeof(bound), "%.1f", kMaxSweepSpan_s);
    return std::to_string(span_s) + " s, more than " + bound +
           " s (a sweep lasts 0.05-0.2 s; wrong unit?)";
}

struct BagReader::Impl {
    std::filesystem::path path;
    std::string cloud_topic;
    rosbag::Bag bag;
    std::unique_ptr<rosbag::View> view;
    rosbag::View::iterator it;
    bool skip_bad = false;
    std::size_t sweeps = 0, read = 0, skipped = 0;
    std::vector<StampedPose2> odometry;

    // A message that cannot be used: an error naming it, or with skip_bad a warning (the first
    // only: a damaged stretch can hold thousands) and a count.
    void bad(const std::string& topic, std::size_t k, double stamp_s, const std::string& problem) {
        const std::string what = topic + " message " + std::to_string(k) + " (bag time " +
                                 seconds_text(stamp_s) + " s): " + problem;
        if (!skip_bad)
            throw io::FileError(path.string(),
                                what + " (--skip-bad-messages to skip such messages)");
        if (skipped++ == 0)
            io::print_warning(path.string() + ": " + what +
                              "; skipped (more are counted in the summary)");
    }
};

BagReader::BagReader(const std::filesystem::path& path, const BagTopics& topics,
                     bool require_odometry, bool skip_bad_messages)
    : impl_(std::make_unique<Impl>()) {
    impl_->path = path;
    impl_->skip_bad = skip_bad_messages;
    impl_->cloud_topic = topics.cloud;
    check_bag_structure(path);  // before rosbag trusts its lengths
    captured_console().take();
    try {
        impl_->bag.open(path.string(), rosbag::bagmode::Read);
        const auto types = topic_types(impl_->bag);
        check_topic(path, types, topics.cloud, kCloudType, "--cloud-topic");
        if (require_odometry || types.count(topics.odometry))
            check_topic(path, types, topics.odometry, kOdometryType, "--odom-topic");
        if (types.count(topics.odometry)) {
            rosbag::View odom(impl_->bag, rosbag::TopicQuery(topics.odometry));
            std::size_t k = 0;
            for (const rosbag::MessageInstance& m : odom) {
                try {
                    const auto msg = deserialise<nav_msgs::Odometry>(m);
                    const double stamp =
                        msg.header.stamp.isZero() ? m.getTime().toSec() : msg.header.stamp.toSec();
                    impl_->odometry.push_back({stamp, pose_from_odometry(msg)});
                } catch (const io::FormatError& e) {
                    impl_->bad(topics.odometry, k, m.getTime().toSec(), e.what());
                } catch (const ros::Exception& e) {
                    impl_->bad(topics.odometry, k, m.getTime().toSec(),
                               std::string("does not deserialise: ") + e.what());
                }
                ++k;
            }
            std::stable_sort(
                impl_->odometry.begin(), impl_->odometry.end(),
                [](const StampedPose2& a, const StampedPose2& b) { return a.stamp_s < b.stamp_s; });
        }
        impl_->view = std::make_unique<rosbag::View>(impl_->bag, rosbag::TopicQuery(topics.cloud));
        impl_->sweeps = impl_->view->size();
        impl_->it = impl_->view->begin();
    } catch (const ros::Exception& e) {  // rosbag's BagException is one
        throw io::FileError(path.string(), std::string("not a readable ROS 1 bag: ") + e.what());
    }
    warn_captured(path);
}

BagReader::~BagReader() = default;

std::size_t BagReader::sweeps() const { return impl_->sweeps; }
std::size_t BagReader::skipped() const { return impl_->skipped; }
const std::vector<StampedPose2>& BagReader::odometry() const { return impl_->odometry; }

std::optional<CloudSweep> BagReader::next() {
    try {
        for (; impl_->it != impl_->view->end();) {
            const std::size_t k = impl_->read++;
            const double bag_time = impl_->it->getTime().toSec();
            std::string problem;
            try {
                const auto msg = deserialise<sensor_msgs::PointCloud2>(*impl_->it);
                CloudSweep s = from_point_cloud2(msg);
                if (msg.header.stamp.isZero()) s.stamp_s += bag_time;
                s.index = k;
                ++impl_->it;
                warn_captured(impl_->path);
                return s;
            } catch (const io::FormatError& e) {
                problem = e.what();
            }
            ++impl_->it;
            impl_->bad(impl_->cloud_topic, k, bag_time, problem);
        }
    } catch (const ros::Exception& e) {
        throw io::FileError(impl_->path.string(), std::string("unreadable: ") + e.what());
    }
    return std::nullopt;
}

std::map<std::string, BagTopic> bag_topics(const std::filesystem::path& path) {
    check_bag_structure(path);
    captured_console().take();
    std::map<std::string, BagTopic> out;
    try {
        rosbag::Bag bag(path.string(), rosbag::bagmode::Read);
        for (const auto& [topic, type] : topic_types(bag)) {
            rosbag::View view(bag, rosbag::TopicQuery(topic));
            out[topic] = {type, view.size()};
        }
    } catch (const ros::Exception& e) {
        throw io::FileError(path.string(), std::string("not a readable ROS 1 bag: ") + e.what());
    }
    warn_captured(path);
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

void BagWriter::write_cloud(const std::string& topic, const PointCloud& cloud, double stamp_s,
                            const std::string& frame_id) {
    impl_->write(topic, stamp_s, to_point_cloud2(cloud, stamp_s, frame_id));
}

void BagWriter::write_odometry(const std::string& topic, const Pose2& pose, double v_mps,
                               double w_radps, double stamp_s, const std::string& frame_id,
                               const std::string& child_frame_id) {
    impl_->write(topic, stamp_s,
                 to_odometry(pose, v_mps, w_radps, stamp_s, frame_id, child_frame_id));
}

void BagWriter::write_costmap(const std::string& topic, const Costmap& costmap, double stamp_s,
                              const std::string& frame_id) {
    impl_->write(topic, stamp_s, to_occupancy_grid(costmap, stamp_s, frame_id));
}

void BagWriter::write_markers(const std::string& topic, const std::vector<ObjectEstimate>& objects,
                              const costmap::AffordanceParams& zones, double stamp_s,
                              const std::string& frame_id) {
    impl_->write(topic, stamp_s, to_markers(objects, zones, stamp_s, frame_id));
}

void BagWriter::write_tf(const Isometry3& T_parent_child, double stamp_s, const std::string& parent,
                         const std::string& child, bool is_static) {
    impl_->write(is_static ? "/tf_static" : "/tf", stamp_s,
                 to_tf(T_parent_child, stamp_s, parent, child));
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

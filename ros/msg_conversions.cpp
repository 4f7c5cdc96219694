#include "ros/msg_conversions.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

#include "io/error.hpp"
#include "io/pose_io.hpp"
#include "makeway/common/angles.hpp"

namespace makeway::rosio {
namespace {

using sensor_msgs::PointField;

std::size_t field_size(std::uint8_t datatype) {
    switch (datatype) {
        case PointField::INT8:
        case PointField::UINT8:
            return 1;
        case PointField::INT16:
        case PointField::UINT16:
            return 2;
        case PointField::INT32:
        case PointField::UINT32:
        case PointField::FLOAT32:
            return 4;
        case PointField::FLOAT64:
            return 8;
        default:
            return 0;
    }
}

template <typename T>
T load(const std::uint8_t* p) {
    T v;
    std::memcpy(&v, p, sizeof(T));
    return v;
}

double read_number(const std::uint8_t* p, std::uint8_t datatype) {
    switch (datatype) {
        case PointField::INT8:
            return load<std::int8_t>(p);
        case PointField::UINT8:
            return load<std::uint8_t>(p);
        case PointField::INT16:
            return load<std::int16_t>(p);
        case PointField::UINT16:
            return load<std::uint16_t>(p);
        case PointField::INT32:
            return load<std::int32_t>(p);
        case PointField::UINT32:
            return load<std::uint32_t>(p);
        case PointField::FLOAT32:
            return load<float>(p);
        default:
            return load<double>(p);
    }
}

const PointField* find_field(const sensor_msgs::PointCloud2& msg, const std::string& name) {
    for (const PointField& f : msg.fields) {
        if (f.name == name) return &f;
    }
    return nullptr;
}

PointField make_field(const std::string& name, std::uint32_t offset, std::uint8_t datatype) {
    PointField f;
    f.name = name;
    f.offset = offset;
    f.datatype = datatype;
    f.count = 1;
    return f;
}

geometry_msgs::Quaternion quaternion_of_yaw(double yaw) {
    geometry_msgs::Quaternion q;
    q.w = std::cos(0.5 * yaw);
    q.z = std::sin(0.5 * yaw);
    return q;
}

}  // namespace

ros::Time to_ros_time(double stamp_s) { return ros::Time(std::max(stamp_s, 1e-9)); }

CloudSweep from_point_cloud2(const sensor_msgs::PointCloud2& msg) {
    if (msg.is_bigendian) throw io::FormatError("big-endian PointCloud2 data is not supported");
    const std::size_t n = static_cast<std::size_t>(msg.width) * msg.height;
    if (n > 0 && msg.point_step == 0) throw io::FormatError("point_step is 0");
    if (msg.height > 0 && msg.row_step < static_cast<std::uint64_t>(msg.width) * msg.point_step) {
        throw io::FormatError("row_step " + std::to_string(msg.row_step) +
                              " is shorter than width x point_step");
    }
    if (static_cast<std::uint64_t>(msg.row_step) * msg.height > msg.data.size()) {
        throw io::FormatError(
            "data holds " + std::to_string(msg.data.size()) + " bytes, row_step x height needs " +
            std::to_string(static_cast<std::uint64_t>(msg.row_step) * msg.height));
    }
    for (const PointField& f : msg.fields) {
        const std::size_t size = field_size(f.datatype);
        if (size == 0)
            throw io::FormatError("field '" + f.name + "' has unknown datatype " +
                                  std::to_string(f.datatype));
        if (static_cast<std::uint64_t>(f.offset) + size * std::max<std::uint32_t>(f.count, 1) >
            msg.point_step) {
            throw io::FormatError("field '" + f.name + "' lies outside the point (offset " +
                                  std::to_string(f.offset) + ", point_step " +
                                  std::to_string(msg.point_step) + ")");
        }
    }
    const PointField* fx = find_field(msg, "x");
    const PointField* fy = find_field(msg, "y");
    const PointField* fz = find_field(msg, "z");
    if (!fx || !fy || !fz) throw io::FormatError("the cloud has no x, y and z fields");
    for (const PointField* f : {fx, fy, fz}) {
        if (f->datatype != PointField::FLOAT32 && f->datatype != PointField::FLOAT64) {
            throw io::FormatError("field '" + f->name + "' must be float32 or float64");
        }
    }
    // A coordinate declared wider than its slot (x as float64 over x and y's bytes) reads garbage
    // that looks like points.
    const PointField* xyz[3] = {fx, fy, fz};
    for (int a = 0; a < 3; ++a) {
        for (int b = a + 1; b < 3; ++b) {
            const std::uint64_t a0 = xyz[a]->offset, a1 = a0 + field_size(xyz[a]->datatype);
            const std::uint64_t b0 = xyz[b]->offset, b1 = b0 + field_size(xyz[b]->datatype);
            if (a0 < b1 && b0 < a1) {
                throw io::FormatError("fields '" + xyz[a]->name + "' and '" + xyz[b]->name +
                                      "' overlap (offsets " + std::to_string(a0) + " and " +
                                      std::to_string(b0) + ", " + std::to_string(a1 - a0) +
                                      " and " + std::to_string(b1 - b0) + " bytes)");
            }
        }
    }
    if (n == 0)
        throw io::FormatError("the cloud holds no points (width " + std::to_string(msg.width) +
                              ", height " + std::to_string(msg.height) + ")");
    const PointField* fi = find_field(msg, "intensity");
    const PointField* fr = find_field(msg, "ring");
    // The time field and how to read it: a relative offset from the stamp, or absolute.
    const PointField* ft = nullptr;
    CloudSweep out;
    double scale = 1.0;
    bool absolute = false;
    if ((ft = find_field(msg, "time"))) {
        out.time_field = "time";
    } else if ((ft = find_field(msg, "t"))) {
        out.time_field = "t";
        if (ft->datatype != PointField::FLOAT32 && ft->datatype != PointField::FLOAT64)
            scale = 1e-9;  // Ouster: ns
    } else if ((ft = find_field(msg, "timestamp"))) {
        out.time_field = "timestamp";
        absolute = true;
    }

    PointFields fields;
    fields.intensity = fi != nullptr;
    fields.ring = fr != nullptr;
    fields.time = ft != nullptr;
    out.points.resize(n, fields);
    std::vector<double> t_abs(ft ? n : 0);
    const double stamp = msg.header.stamp.toSec();
    std::size_t k = 0;
    for (std::uint32_t row = 0; row < msg.height; ++row) {
        const std::uint8_t* base = msg.data.data() + static_cast<std::size_t>(row) * msg.row_step;
        for (std::uint32_t col = 0; col < msg.width; ++col, ++k) {
            const std::uint8_t* p = base + static_cast<std::size_t>(col) * msg.point_step;
            out.points.xyz[k] =
                Eigen::Vector3f(static_cast<float>(read_number(p + fx->offset, fx->datatype)),
                                static_cast<float>(read_number(p + fy->offset, fy->datatype)),
                                static_cast<float>(read_number(p + fz->offset, fz->datatype)));
            if (fi)
                out.points.intensity[k] =
                    static_cast<float>(read_number(p + fi->offset, fi->datatype));
            if (fr)
                out.points.ring[k] = static_cast<std::uint16_t>(
                    std::clamp(read_number(p + fr->offset, fr->datatype), 0.0, 65535.0));
            if (ft) {
                const double v = read_number(p + ft->offset, ft->datatype) * scale;
                if (ft->datatype == PointField::FLOAT64 && v > 1e6) absolute = true;
                t_abs[k] = absolute ? v : stamp + v;
            }
        }
    }
    out.stamp_s = stamp;
    out.frame_id = msg.header.frame_id;
    if (ft && n > 0) {
        double first = std::numeric_limits<double>::infinity(), last = -first;
        for (double t : t_abs) {
            if (!std::isfinite(t))
                throw io::FormatError("field '" + out.time_field + "' holds a non-finite time");
            first = std::min(first, t), last = std::max(last, t);
        }
        // Relative times that are all >= 0: the stamp is the sweep's start (its first firing may
        // have returned nothing). Negative ones (drivers that stamp the end): the first point.
        if (!absolute && first > stamp) first = stamp;
        if (const std::string p = sweep_span_problem(last - first); !p.empty())
            throw io::FormatError("field '" + out.time_field + "' spans " + p);
        out.timed = true;
        out.stamp_s = first;
        out.duration_s = last - first;
        for (std::size_t i = 0; i < n; ++i)
            out.points.time_s[i] = static_cast<float>(t_abs[i] - first);
    }
    return out;
}

sensor_msgs::PointCloud2 to_point_cloud2(const PointCloud& cloud, double stamp_s,
                                         const std::string& frame_id) {
    sensor_msgs::PointCloud2 msg;
    msg.header.stamp = to_ros_time(stamp_s);
    msg.header.frame_id = frame_id;
    msg.height = 1;
    msg.width = static_cast<std::uint32_t>(cloud.size());
    msg.fields = {make_field("x", 0, PointField::FLOAT32),
                  make_field("y", 4, PointField::FLOAT32),
                  make_field("z", 8, PointField::FLOAT32),
                  make_field("intensity", 12, PointField::FLOAT32),
                  make_field("ring", 16, PointField::UINT16),
                  make_field("time", 18, PointField::FLOAT32)};
    msg.point_step = 22;
    msg.row_step = msg.point_step * msg.width;
    msg.is_bigendian = false;
    msg.is_dense = true;
    msg.data.resize(static_cast<std::size_t>(msg.row_step));
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        std::uint8_t* p = msg.data.data() + i * msg.point_step;
        const float values[4] = {cloud.xyz[i].x(), cloud.xyz[i].y(), cloud.xyz[i].z(),
                                 cloud.intensity.empty() ? 0.0f : cloud.intensity[i]};
        const std::uint16_t ring = cloud.ring.empty() ? 0 : cloud.ring[i];
        const float time = cloud.time_s.empty() ? 0.0f : cloud.time_s[i];
        std::memcpy(p, values, sizeof(values));
        std::memcpy(p + 16, &ring, sizeof(ring));
        std::memcpy(p + 18, &time, sizeof(time));
        msg.is_dense = msg.is_dense && cloud.xyz[i].allFinite();
    }
    return msg;
}

Pose2 pose_from_odometry(const nav_msgs::Odometry& msg) {
    const auto& t = msg.pose.pose.position;
    if (!std::isfinite(t.x) || !std::isfinite(t.y) || !std::isfinite(t.z))
        throw io::FormatError("the position is not finite");
    if (std::hypot(t.x, t.y, t.z) > io::kMaxPosition_m) {
        throw io::FormatError("the position lies " + std::to_string(std::hypot(t.x, t.y, t.z)) +
                              " m from the origin (more than " +
                              std::to_string(static_cast<int>(io::kMaxPosition_m / 1000)) + " km)");
    }
    const auto& o = msg.pose.pose.orientation;
    const double norm = std::sqrt(o.x * o.x + o.y * o.y + o.z * o.z + o.w * o.w);
    if (!std::isfinite(norm) || norm < 1e-6)
        throw io::FormatError("the orientation quaternion is zero or not finite");
    const Eigen::Vector4d q =
        Eigen::Vector4d(o.x, o.y, o.z, o.w) / norm;  // drivers round; some never normalise
    const double yaw = std::atan2(2.0 * (q.w() * q.z() + q.x() * q.y()),
                                  1.0 - 2.0 * (q.y() * q.y() + q.z() * q.z()));
    return {msg.pose.pose.position.x, msg.pose.pose.position.y, yaw};
}

nav_msgs::Odometry to_odometry(const Pose2& pose, double v_mps, double w_radps, double stamp_s,
                               const std::string& frame_id, const std::string& child_frame_id) {
    nav_msgs::Odometry msg;
    msg.header.stamp = to_ros_time(stamp_s);
    msg.header.frame_id = frame_id;
    msg.child_frame_id = child_frame_id;
    msg.pose.pose.position.x = pose.x_m;
    msg.pose.pose.position.y = pose.y_m;
    msg.pose.pose.orientation = quaternion_of_yaw(pose.yaw_rad);
    msg.twist.twist.linear.x = v_mps;
    msg.twist.twist.angular.z = w_radps;
    return msg;
}

std::int8_t occupancy_of_cost(std::uint8_t cost) {
    if (cost == cost::kFree) return 0;
    if (cost == cost::kUnknown) return -1;
    if (cost == cost::kLethal) return 100;
    if (cost == cost::kInscribed) return 99;
    return static_cast<std::int8_t>(1 + (97 * (cost - 1)) / 251);
}

nav_msgs::OccupancyGrid to_occupancy_grid(const Costmap& costmap, double stamp_s,
                                          const std::string& frame_id) {
    nav_msgs::OccupancyGrid msg;
    msg.header.stamp = to_ros_time(stamp_s);
    msg.header.frame_id = frame_id;
    msg.info.map_load_time = msg.header.stamp;
    msg.info.resolution = static_cast<float>(costmap.resolution_m);
    msg.info.width = static_cast<std::uint32_t>(costmap.width);
    msg.info.height = static_cast<std::uint32_t>(costmap.height);
    msg.info.origin.position.x = costmap.origin_m.x();
    msg.info.origin.position.y = costmap.origin_m.y();
    msg.info.origin.orientation.w = 1.0;
    msg.data.resize(costmap.cost.size());
    std::transform(costmap.cost.begin(), costmap.cost.end(), msg.data.begin(), occupancy_of_cost);
    return msg;
}

visualization_msgs::MarkerArray to_markers(const std::vector<ObjectEstimate>& objects,
                                           const costmap::AffordanceParams& zones, double stamp_s,
                                           const std::string& frame_id) {
    using visualization_msgs::Marker;
    visualization_msgs::MarkerArray array;
    Marker clear;
    clear.header.stamp = to_ros_time(stamp_s);
    clear.header.frame_id = frame_id;
    clear.action = Marker::DELETEALL;
    array.markers.push_back(clear);
    for (const ObjectEstimate& o : objects) {
        const bool chair = o.cls == ObjectClass::kChair;
        Marker box = clear;
        box.action = Marker::ADD;
        box.ns = "objects";
        box.id = static_cast<std::int32_t>(o.id);
        box.type = Marker::CUBE;
        box.pose.position.x = o.box_world.centre_m.x();
        box.pose.position.y = o.box_world.centre_m.y();
        box.pose.position.z = o.box_world.centre_m.z();
        box.pose.orientation = quaternion_of_yaw(o.box_world.yaw_rad);
        box.scale.x = o.box_world.size_m.x();
        box.scale.y = o.box_world.size_m.y();
        box.scale.z = o.box_world.size_m.z();
        box.color.r = chair ? 0.9f : 0.2f;
        box.color.g = chair ? 0.5f : 0.4f;
        box.color.b = chair ? 0.1f : 0.9f;
        box.color.a = static_cast<float>(0.2 + 0.6 * std::clamp(o.existence, 0.0, 1.0));
        array.markers.push_back(box);

        Marker label = box;
        label.ns = "labels";
        label.type = Marker::TEXT_VIEW_FACING;
        label.pose.position.z = o.box_world.centre_m.z() + 0.5 * o.box_world.size_m.z() + 0.2;
        label.scale = {};
        label.scale.z = 0.2;
        label.color.r = label.color.g = label.color.b = label.color.a = 1.0f;
        char text[64];
        std::snprintf(text, sizeof(text), "%s %u p=%.2f", std::string(to_string(o.cls)).c_str(),
                      o.id, o.existence);
        label.text = text;
        array.markers.push_back(label);

        if (o.existence < zones.min_existence) continue;
        Marker zone = box;
        zone.ns = "zones";
        zone.type = Marker::LINE_STRIP;
        zone.pose = {};
        zone.pose.orientation.w = 1.0;
        zone.scale = {};
        zone.scale.x = 0.03;
        zone.color.a = 1.0f;
        std::vector<Eigen::Vector2d> outline = costmap::zone_outline(o, zones);
        if (!outline.empty()) outline.push_back(outline.front());
        for (const Eigen::Vector2d& p : outline) {
            geometry_msgs::Point q;
            q.x = p.x();
            q.y = p.y();
            q.z = 0.02;
            zone.points.push_back(q);
        }
        array.markers.push_back(zone);
    }
    return array;
}

tf2_msgs::TFMessage to_tf(const Isometry3& T, double stamp_s, const std::string& parent,
                          const std::string& child) {
    geometry_msgs::TransformStamped t;
    t.header.stamp = to_ros_time(stamp_s);
    t.header.frame_id = parent;
    t.child_frame_id = child;
    t.transform.translation.x = T.translation().x();
    t.transform.translation.y = T.translation().y();
    t.transform.translation.z = T.translation().z();
    const Eigen::Quaterniond q(T.linear());
    t.transform.rotation.w = q.w();
    t.transform.rotation.x = q.x();
    t.transform.rotation.y = q.y();
    t.transform.rotation.z = q.z();
    tf2_msgs::TFMessage msg;
    msg.transforms.push_back(t);
    return msg;
}

}  // namespace makeway::rosio

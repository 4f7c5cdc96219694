#pragma once
// A message that claims any type and serialises to any bytes: the damaged or lying messages a
// recording can hold, written with rosbag itself (tests; C++17, as ROS 1's headers need).
#include <ros/message_traits.h>
#include <ros/serialization.h>
#include <rosbag/message_instance.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace makeway::testing {
struct LyingMessage {
    std::vector<std::uint8_t> bytes;
    std::string type, md5, definition;
};
}  // namespace makeway::testing

namespace ros {
namespace message_traits {
template <>
struct MD5Sum<makeway::testing::LyingMessage> {
    static const char* value(const makeway::testing::LyingMessage& m) { return m.md5.c_str(); }
};
template <>
struct DataType<makeway::testing::LyingMessage> {
    static const char* value(const makeway::testing::LyingMessage& m) { return m.type.c_str(); }
};
template <>
struct Definition<makeway::testing::LyingMessage> {
    static const char* value(const makeway::testing::LyingMessage& m) {
        return m.definition.c_str();
    }
};
}  // namespace message_traits
namespace serialization {
template <>
struct Serializer<makeway::testing::LyingMessage> {
    template <typename Stream>
    static void write(Stream& stream, const makeway::testing::LyingMessage& m) {
        if (!m.bytes.empty())
            std::memcpy(stream.advance(static_cast<std::uint32_t>(m.bytes.size())), m.bytes.data(),
                        m.bytes.size());
    }
    static std::uint32_t serializedLength(const makeway::testing::LyingMessage& m) {
        return static_cast<std::uint32_t>(m.bytes.size());
    }
};
}  // namespace serialization
}  // namespace ros

namespace makeway::testing {

/// A real message's bytes under its own type, ready to be damaged.
template <typename M>
LyingMessage as_bytes(const M& msg) {
    LyingMessage out;
    out.bytes.resize(ros::serialization::serializationLength(msg));
    ros::serialization::OStream s(out.bytes.data(), static_cast<std::uint32_t>(out.bytes.size()));
    ros::serialization::serialize(s, msg);
    out.type = ros::message_traits::datatype(msg);
    out.md5 = ros::message_traits::md5sum(msg);
    out.definition = ros::message_traits::definition(msg);
    return out;
}

/// A message of a bag as it is, whatever its type (to copy a recording with some messages damaged).
inline LyingMessage as_bytes(const rosbag::MessageInstance& m) {
    LyingMessage out;
    out.bytes.resize(m.size());
    ros::serialization::OStream s(out.bytes.data(), static_cast<std::uint32_t>(out.bytes.size()));
    m.write(s);
    out.type = m.getDataType();
    out.md5 = m.getMD5Sum();
    out.definition = m.getMessageDefinition();
    return out;
}

}  // namespace makeway::testing

#include "makeway/common/point_cloud.hpp"

#include <stdexcept>

namespace makeway {
namespace {

template <typename T>
void resize_channel(std::vector<T>& channel, bool present, std::size_t n) {
    if (present) {
        channel.assign(n, T{});
    } else {
        channel.clear();
    }
}

template <typename T>
void select_channel(const std::vector<T>& in, const std::vector<std::size_t>& indices,
                    std::vector<T>& out) {
    if (in.empty()) return;
    out.reserve(indices.size());
    for (std::size_t i : indices) out.push_back(in[i]);
}

template <typename T>
void append_channel(std::vector<T>& dst, const std::vector<T>& src) {
    dst.insert(dst.end(), src.begin(), src.end());
}

bool is_finite(const Eigen::Vector3f& p) { return p.allFinite(); }

}  // namespace

PointFields PointCloud::fields() const {
    return {!intensity.empty(), !ring.empty(), !time_s.empty(), !label.empty(), !instance.empty()};
}

void PointCloud::resize(std::size_t n, PointFields f) {
    xyz.assign(n, Eigen::Vector3f::Zero());
    resize_channel(intensity, f.intensity, n);
    resize_channel(ring, f.ring, n);
    resize_channel(time_s, f.time, n);
    resize_channel(label, f.label, n);
    resize_channel(instance, f.instance, n);
}

std::string PointCloud::consistency_error() const {
    const std::size_t n = xyz.size();
    auto check = [n](const char* name, std::size_t len) -> std::string {
        if (len == 0 || len == n) return {};
        return std::string(name) + " has " + std::to_string(len) + " values for " +
               std::to_string(n) + " points";
    };
    for (const auto& msg : {check("intensity", intensity.size()), check("ring", ring.size()),
                            check("time", time_s.size()), check("label", label.size()),
                            check("instance", instance.size())}) {
        if (!msg.empty()) return msg;
    }
    return {};
}

std::size_t PointCloud::count_non_finite() const {
    std::size_t count = 0;
    for (const auto& p : xyz) count += is_finite(p) ? 0 : 1;
    return count;
}

PointCloud PointCloud::select(const std::vector<std::size_t>& indices) const {
    PointCloud out;
    select_channel(xyz, indices, out.xyz);
    select_channel(intensity, indices, out.intensity);
    select_channel(ring, indices, out.ring);
    select_channel(time_s, indices, out.time_s);
    select_channel(label, indices, out.label);
    select_channel(instance, indices, out.instance);
    return out;
}

void PointCloud::append(const PointCloud& other) {
    if (other.empty()) return;
    if (!empty() && fields() != other.fields()) {
        throw std::invalid_argument("PointCloud::append: clouds carry different channels");
    }
    append_channel(xyz, other.xyz);
    append_channel(intensity, other.intensity);
    append_channel(ring, other.ring);
    append_channel(time_s, other.time_s);
    append_channel(label, other.label);
    append_channel(instance, other.instance);
}

void PointCloud::reserve(std::size_t n, PointFields f) {
    xyz.reserve(n);
    if (f.intensity) intensity.reserve(n);
    if (f.ring) ring.reserve(n);
    if (f.time) time_s.reserve(n);
    if (f.label) label.reserve(n);
    if (f.instance) instance.reserve(n);
}

PointCloud PointCloud::transformed(const Eigen::Isometry3d& T) const {
    PointCloud out = *this;
    const Eigen::Isometry3f Tf = T.cast<float>();
    for (auto& p : out.xyz) p = Tf * p;
    return out;
}

PointBounds compute_bounds(const PointCloud& cloud) {
    PointBounds b;
    for (const auto& p : cloud.xyz) {
        if (!is_finite(p)) continue;
        if (!b.valid) {
            b.min_m = b.max_m = p;
            b.valid = true;
        } else {
            b.min_m = b.min_m.cwiseMin(p);
            b.max_m = b.max_m.cwiseMax(p);
        }
    }
    return b;
}

PointCloud remove_non_finite(const PointCloud& cloud) {
    std::vector<std::size_t> keep;
    keep.reserve(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (is_finite(cloud.xyz[i])) keep.push_back(i);
    }
    return cloud.select(keep);
}

}  // namespace makeway

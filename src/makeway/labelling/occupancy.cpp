#include "makeway/labelling/occupancy.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "makeway/labelling/param_tables.hpp"

namespace makeway::labelling {

std::string_view to_string(PointClass c) {
    switch (c) {
        case PointClass::kGround:
            return "ground";
        case PointClass::kPermanent:
            return "permanent";
        case PointClass::kMovable:
            return "movable";
        case PointClass::kDynamic:
            return "dynamic";
    }
    return "?";
}

std::vector<std::string> OccupancyParams::validate() const {
    std::vector<std::string> e;
    for (const std::string& s : occupancy_table().problems(*this)) e.push_back("labelling." + s);
    if (!(max_range_m > 0.0)) e.push_back("labelling.max_range_m must be > 0");
    return e;
}

MultiSessionOccupancy::MultiSessionOccupancy(const OccupancyParams& params,
                                             const Eigen::AlignedBox3d& bounds, int sessions)
    : params_(params), sessions_(sessions) {
    if (sessions < 1) throw std::invalid_argument("occupancy: at least one session");
    if (bounds.isEmpty()) throw std::invalid_argument("occupancy: empty bounds");
    origin_ = bounds.min();
    const Eigen::Vector3d extent = bounds.sizes() / params.voxel_m;
    dims_ = (extent.array().ceil() + 1.0).cast<int>().matrix();
    voxels_ = static_cast<std::size_t>(dims_.x()) * static_cast<std::size_t>(dims_.y()) *
              static_cast<std::size_t>(dims_.z());
    if (voxels_ * static_cast<std::size_t>(sessions) > params.max_voxels) {
        throw std::invalid_argument("occupancy: the sessions span " + std::to_string(voxels_) +
                                    " voxels of " + std::to_string(params.voxel_m) +
                                    " m, more than the " + std::to_string(params.max_voxels) +
                                    " allowed (a larger labelling.voxel_m or fewer sessions)");
    }
    cells_.assign(voxels_ * static_cast<std::size_t>(sessions), Cell{});
}

bool MultiSessionOccupancy::index_of(const Eigen::Vector3d& p, Eigen::Vector3i& v) const {
    const Eigen::Vector3d f = (p - origin_) / params_.voxel_m;
    if (!f.allFinite()) return false;
    v = f.array().floor().cast<int>().matrix();
    return (v.array() >= 0).all() && (v.array() < dims_.array()).all();
}

void MultiSessionOccupancy::add_sweep(int session, const Eigen::Vector3d& origin,
                                      const std::vector<Eigen::Vector3f>& points_world) {
    if (session < 0 || session >= sessions_) throw std::out_of_range("occupancy: no such session");
    const std::uint32_t stamp = ++sweep_;
    const double h = params_.voxel_m;
    for (const Eigen::Vector3f& pf : points_world) {
        const Eigen::Vector3d p = pf.cast<double>();
        const Eigen::Vector3d d = p - origin;
        const double range = d.norm();
        if (!(range > 1e-6) || !std::isfinite(range)) continue;
        Eigen::Vector3i v;
        if (range <= params_.max_range_m && index_of(p, v)) {
            Cell& c = cell(session, flat(v));
            if (c.last_hit != stamp) {
                c.last_hit = stamp;
                if (c.hits < UINT16_MAX) ++c.hits;
            }
        }
        // Free space: Amanatides & Woo's voxel walk from the origin to the end of the free part.
        const double free_len = std::min(
            range - params_.end_margin_m - params_.range_margin * range, params_.max_range_m);
        if (free_len <= 0.0) continue;
        const Eigen::Vector3d dir = d / range;
        const Eigen::Vector3d start_f = (origin - origin_) / h;
        Eigen::Vector3i cur = start_f.array().floor().cast<int>().matrix();
        Eigen::Vector3i step;
        Eigen::Vector3d t_max, t_delta;
        for (int a = 0; a < 3; ++a) {
            if (dir[a] > 0) {
                step[a] = 1;
                t_max[a] = (std::floor(start_f[a]) + 1.0 - start_f[a]) * h / dir[a];
                t_delta[a] = h / dir[a];
            } else if (dir[a] < 0) {
                step[a] = -1;
                t_max[a] = (start_f[a] - std::floor(start_f[a])) * h / -dir[a];
                t_delta[a] = h / -dir[a];
            } else {
                step[a] = 0;
                t_max[a] = t_delta[a] = std::numeric_limits<double>::infinity();
            }
        }
        double t = 0.0;
        while (t < free_len) {
            if ((cur.array() >= 0).all() && (cur.array() < dims_.array()).all()) {
                Cell& c = cell(session, flat(cur));
                if (c.last_free != stamp) {
                    c.last_free = stamp;
                    if (c.free < UINT16_MAX) ++c.free;
                }
            }
            int a = 0;
            if (t_max[1] < t_max[a]) a = 1;
            if (t_max[2] < t_max[a]) a = 2;
            t = t_max[a];
            t_max[a] += t_delta[a];
            cur[a] += step[a];
        }
    }
}

MultiSessionOccupancy::Evidence MultiSessionOccupancy::evidence(
    int session, const Eigen::Vector3d& p_world) const {
    Eigen::Vector3i v;
    if (session < 0 || session >= sessions_ || !index_of(p_world, v)) return {};
    const Cell& c = cell(session, flat(v));
    return {c.hits, c.free};
}

PointClass MultiSessionOccupancy::classify(int session, const Eigen::Vector3d& p_world) const {
    const Evidence own = evidence(session, p_world);
    if (own.free >= params_.dynamic_min_free && own.hits < params_.dynamic_hit_ratio * own.free)
        return PointClass::kDynamic;
    for (int s = 0; s < sessions_; ++s) {
        if (s == session) continue;
        const Evidence other = evidence(s, p_world);
        if (other.free >= params_.min_free_sweeps &&
            other.hits <= params_.absent_hit_ratio * other.free)
            return PointClass::kMovable;
    }
    return PointClass::kPermanent;
}

}  // namespace makeway::labelling

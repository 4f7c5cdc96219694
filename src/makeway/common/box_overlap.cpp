#include "makeway/common/box_overlap.hpp"

#include <algorithm>
#include <cmath>

#include "makeway/common/polygon2d.hpp"

namespace makeway {
namespace {

Polygon2 footprint(const OrientedBox& box) {
    const auto c = box.bev_corners();
    return Polygon2(c.begin(), c.end());
}

}  // namespace

double bev_intersection_area_m2(const OrientedBox& a, const OrientedBox& b) {
    return std::max(0.0, signed_area(clip_convex(footprint(a), footprint(b))));
}

double iou_bev(const OrientedBox& a, const OrientedBox& b) {
    const double inter = bev_intersection_area_m2(a, b);
    const double uni = a.size_m.x() * a.size_m.y() + b.size_m.x() * b.size_m.y() - inter;
    return uni > 0.0 ? std::clamp(inter / uni, 0.0, 1.0) : 0.0;
}

BoxOverlap box_overlap_3d(const OrientedBox& a, const OrientedBox& b) {
    BoxOverlap r;
    const double overlap_h =
        std::max(0.0, std::min(a.z_max_m(), b.z_max_m()) - std::max(a.z_min_m(), b.z_min_m()));
    const double inter_area = overlap_h > 0.0 ? bev_intersection_area_m2(a, b) : 0.0;
    r.intersection_m3 = inter_area * overlap_h;
    r.union_m3 = std::max(0.0, a.volume_m3() + b.volume_m3() - r.intersection_m3);

    Polygon2 all = footprint(a);
    const Polygon2 fb = footprint(b);
    all.insert(all.end(), fb.begin(), fb.end());
    const double hull_area = std::max(0.0, signed_area(convex_hull(std::move(all))));
    const double span_h = std::max(a.z_max_m(), b.z_max_m()) - std::min(a.z_min_m(), b.z_min_m());
    r.enclosing_m3 = std::max(hull_area * span_h, r.union_m3);

    r.iou = r.union_m3 > 0.0 ? std::clamp(r.intersection_m3 / r.union_m3, 0.0, 1.0) : 0.0;
    r.giou = r.enclosing_m3 > 0.0 ? r.iou - (r.enclosing_m3 - r.union_m3) / r.enclosing_m3 : 0.0;
    return r;
}

}  // namespace makeway

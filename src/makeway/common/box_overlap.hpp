#pragma once
// Exact rotated 3D IoU and GIoU (Rezatofighi et al., CVPR 2019) for yaw-only boxes: the footprint
// polygons are intersected exactly and multiplied by the vertical overlap.
#include "makeway/common/oriented_box.hpp"

namespace makeway {

struct BoxOverlap {
    double intersection_m3 = 0.0;
    double union_m3 = 0.0;
    double enclosing_m3 = 0.0;  ///< convex hull of both footprints x combined height span
    double iou = 0.0;           ///< in [0, 1]; 0 when the union is empty
    double giou = 0.0;          ///< in [-1, 1]; iou - (enclosing - union) / enclosing
};

BoxOverlap box_overlap_3d(const OrientedBox& a, const OrientedBox& b);
inline double iou_3d(const OrientedBox& a, const OrientedBox& b) {
    return box_overlap_3d(a, b).iou;
}
inline double giou_3d(const OrientedBox& a, const OrientedBox& b) {
    return box_overlap_3d(a, b).giou;
}

/// Footprint intersection area [m^2] and bird's-eye-view IoU.
double bev_intersection_area_m2(const OrientedBox& a, const OrientedBox& b);
double iou_bev(const OrientedBox& a, const OrientedBox& b);

}  // namespace makeway

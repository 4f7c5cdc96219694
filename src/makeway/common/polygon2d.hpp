#pragma once
// Small exact 2D polygon routines for box overlap (bird's-eye view).
#include <Eigen/Core>
#include <vector>

namespace makeway {

using Polygon2 = std::vector<Eigen::Vector2d>;

/// Shoelace area, positive for counter-clockwise vertex order [m^2].
double signed_area(const Polygon2& polygon);

/// Intersection of two convex counter-clockwise polygons (Sutherland-Hodgman). Empty when disjoint.
Polygon2 clip_convex(const Polygon2& subject, const Polygon2& clip);

/// Distance from `p` to a convex polygon (either vertex order): 0 inside or on it, else to the
/// nearest edge. An empty polygon is infinitely far.
double convex_distance(const Polygon2& polygon, const Eigen::Vector2d& p);

/// Convex hull, counter-clockwise, collinear points dropped (Andrew's monotone chain).
Polygon2 convex_hull(Polygon2 points);

}  // namespace makeway

// Planar polygon checks and convex decomposition (for extruded obstacles).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace rrlab {

using Polygon2 = std::vector<Eigen::Vector2d>;

// Empty string when the polygon is usable: at least 3 vertices, finite,
// non-zero area, no repeated vertex and no two edges crossing.
std::string polygon_problem(const Polygon2& polygon);
double signed_area(const Polygon2& polygon);  // > 0 counter-clockwise
bool is_convex(const Polygon2& polygon);
// Convex parts covering a simple polygon exactly (ear clipping, then
// Hertel–Mehlhorn merging of triangles across removable diagonals).
std::vector<Polygon2> convex_decomposition(const Polygon2& polygon);

}  // namespace rrlab

// Planar polygon checks and convex decomposition.
//
// Vertex and edge numbers in messages are 0-based (edge i runs from vertex i
// to vertex i+1), like the JSON paths the scenario loader reports.
#include <rrlab/collision/polygon.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

namespace rrlab {

namespace {

// Relative tolerance for collinearity tests, scaled by the edge lengths.
constexpr double kCollinearTolerance = 1e-12;

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Orientation of c relative to the line a-b: +1 left, -1 right, 0 on it.
int orientation(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const double value = cross(b - a, c - a);
  const double scale = kCollinearTolerance * (b - a).norm() * (c - a).norm();
  if (value > scale) return 1;
  if (value < -scale) return -1;
  return 0;
}

// c lies within the bounding box of a-b (used once c is known to be collinear).
bool within_span(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return c.x() <= std::max(a.x(), b.x()) && c.x() >= std::min(a.x(), b.x()) &&
         c.y() <= std::max(a.y(), b.y()) && c.y() >= std::min(a.y(), b.y());
}

// Closed segments p1-p2 and q1-q2 share at least one point.
bool segments_touch(const Eigen::Vector2d& p1, const Eigen::Vector2d& p2,
                    const Eigen::Vector2d& q1, const Eigen::Vector2d& q2) {
  const int o1 = orientation(p1, p2, q1), o2 = orientation(p1, p2, q2);
  const int o3 = orientation(q1, q2, p1), o4 = orientation(q1, q2, p2);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;  // proper crossing
  // an end point on the other segment
  return (o1 == 0 && within_span(p1, p2, q1)) || (o2 == 0 && within_span(p1, p2, q2)) ||
         (o3 == 0 && within_span(q1, q2, p1)) || (o4 == 0 && within_span(q1, q2, p2));
}

std::string first_crossing(const Polygon2& polygon) {
  const int n = static_cast<int>(polygon.size());
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d& p1 = polygon[i];
    const Eigen::Vector2d& p2 = polygon[(i + 1) % n];
    for (int j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // adjacent through vertex 0
      if (segments_touch(p1, p2, polygon[j], polygon[(j + 1) % n]))
        return "edges " + std::to_string(i) + " and " + std::to_string(j) + " cross";
    }
  }
  return "";
}

double bounding_box_diagonal(const Polygon2& polygon) {
  Eigen::Vector2d lo = polygon.front(), hi = polygon.front();
  for (const auto& p : polygon) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

Polygon2 counter_clockwise(const Polygon2& polygon) {
  Polygon2 ccw = polygon;
  if (signed_area(ccw) < 0) std::reverse(ccw.begin(), ccw.end());
  return ccw;
}

// --- ear clipping ------------------------------------------------------------

// p inside or on the boundary of the CCW triangle a-b-c.
bool in_triangle(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                 const Eigen::Vector2d& c) {
  return orientation(a, b, p) >= 0 && orientation(b, c, p) >= 0 && orientation(c, a, p) >= 0;
}

bool is_ear(const Polygon2& pts, const std::vector<int>& ring, int k) {
  const int n = static_cast<int>(ring.size());
  const int ia = ring[(k + n - 1) % n], ib = ring[k], ic = ring[(k + 1) % n];
  const Eigen::Vector2d &a = pts[ia], &b = pts[ib], &c = pts[ic];
  if (orientation(a, b, c) <= 0) return false;  // reflex or straight: not an ear
  for (int other : ring) {
    if (other == ia || other == ib || other == ic) continue;
    if (pts[other] == a || pts[other] == b || pts[other] == c) continue;
    if (in_triangle(pts[other], a, b, c)) return false;
  }
  return true;
}

// Triangles (vertex index triples, CCW) of a simple CCW polygon.
std::vector<std::vector<int>> ear_clip(const Polygon2& pts) {
  std::vector<int> ring(pts.size());
  std::iota(ring.begin(), ring.end(), 0);
  std::vector<std::vector<int>> triangles;
  while (ring.size() > 3) {
    const int n = static_cast<int>(ring.size());
    int ear = -1;
    for (int k = 0; k < n && ear < 0; ++k)
      if (is_ear(pts, ring, k)) ear = k;
    if (ear < 0) {
      // Only straight vertices are left blocking: dropping one loses no area.
      for (int k = 0; k < n && ear < 0; ++k)
        if (orientation(pts[ring[(k + n - 1) % n]], pts[ring[k]], pts[ring[(k + 1) % n]]) == 0)
          ear = k;
      if (ear < 0) break;  // not a simple polygon; polygon_problem reports why
      ring.erase(ring.begin() + ear);
      continue;
    }
    triangles.push_back({ring[(ear + n - 1) % n], ring[ear], ring[(ear + 1) % n]});
    ring.erase(ring.begin() + ear);
  }
  if (ring.size() == 3 && orientation(pts[ring[0]], pts[ring[1]], pts[ring[2]]) > 0)
    triangles.push_back(ring);
  return triangles;
}

// --- Hertel–Mehlhorn ---------------------------------------------------------

bool convex_loop(const Polygon2& pts, const std::vector<int>& loop) {
  const int n = static_cast<int>(loop.size());
  for (int k = 0; k < n; ++k)
    if (orientation(pts[loop[(k + n - 1) % n]], pts[loop[k]], pts[loop[(k + 1) % n]]) < 0)
      return false;
  return true;
}

// Joins loops a and b across their shared edge, if they have one: a runs u->v
// where b runs v->u. Empty when they share no edge.
std::vector<int> join_across_shared_edge(const std::vector<int>& a, const std::vector<int>& b) {
  const int na = static_cast<int>(a.size()), nb = static_cast<int>(b.size());
  for (int i = 0; i < na; ++i) {
    const int u = a[i], v = a[(i + 1) % na];
    for (int j = 0; j < nb; ++j) {
      if (b[j] != v || b[(j + 1) % nb] != u) continue;
      std::vector<int> joined;
      for (int k = 0; k < na; ++k) joined.push_back(a[(i + 1 + k) % na]);  // v ... u
      for (int k = 2; k < nb; ++k) joined.push_back(b[(j + k) % nb]);      // after u ... before v
      return joined;
    }
  }
  return {};
}

// Removes diagonals greedily while the merged part stays convex.
void merge_convex(const Polygon2& pts, std::vector<std::vector<int>>& parts) {
  bool merged_any = true;
  while (merged_any) {
    merged_any = false;
    for (size_t i = 0; i < parts.size() && !merged_any; ++i) {
      for (size_t j = i + 1; j < parts.size() && !merged_any; ++j) {
        std::vector<int> joined = join_across_shared_edge(parts[i], parts[j]);
        if (joined.empty() || !convex_loop(pts, joined)) continue;
        parts[i] = std::move(joined);
        parts.erase(parts.begin() + static_cast<std::ptrdiff_t>(j));
        merged_any = true;
      }
    }
  }
}

// Straight vertices add nothing to a convex part but faces and edges.
Polygon2 without_straight_vertices(const Polygon2& pts, const std::vector<int>& loop) {
  Polygon2 part;
  const int n = static_cast<int>(loop.size());
  for (int k = 0; k < n; ++k) {
    const auto& prev = pts[loop[(k + n - 1) % n]];
    const auto& here = pts[loop[k]];
    const auto& next = pts[loop[(k + 1) % n]];
    if (orientation(prev, here, next) != 0) part.push_back(here);
  }
  return part;
}

}  // namespace

double signed_area(const Polygon2& polygon) {
  double twice_area = 0.0;
  const size_t n = polygon.size();
  for (size_t i = 0; i < n; ++i) twice_area += cross(polygon[i], polygon[(i + 1) % n]);
  return 0.5 * twice_area;
}

std::string polygon_problem(const Polygon2& polygon) {
  if (polygon.size() < 3) return "needs at least 3 points";
  for (const auto& p : polygon)
    if (!p.allFinite()) return "non-finite coordinate";
  for (size_t j = 1; j < polygon.size(); ++j)
    for (size_t i = 0; i < j; ++i)
      if (polygon[i] == polygon[j]) return "repeated vertex " + std::to_string(j);
  if (std::string crossing = first_crossing(polygon); !crossing.empty()) return crossing;
  const double diagonal = bounding_box_diagonal(polygon);
  if (std::abs(signed_area(polygon)) <= kCollinearTolerance * diagonal * diagonal)
    return "zero area";
  return "";
}

bool is_convex(const Polygon2& polygon) {
  const int n = static_cast<int>(polygon.size());
  if (n < 3) return false;
  int left = 0, right = 0;
  double turning = 0.0;  // total exterior angle: ±2π for a simple convex loop
  for (int i = 0; i < n; ++i) {
    const auto& a = polygon[(i + n - 1) % n];
    const auto& b = polygon[i];
    const auto& c = polygon[(i + 1) % n];
    const int o = orientation(a, b, c);
    left += o > 0;
    right += o < 0;
    turning += std::atan2(cross(b - a, c - b), (b - a).dot(c - b));
  }
  if (left > 0 && right > 0) return false;
  return std::abs(std::abs(turning) - 2.0 * std::numbers::pi) < 1e-6;
}

std::vector<Polygon2> convex_decomposition(const Polygon2& polygon) {
  const Polygon2 ccw = counter_clockwise(polygon);
  if (is_convex(ccw)) return {ccw};
  std::vector<std::vector<int>> parts = ear_clip(ccw);
  merge_convex(ccw, parts);
  std::vector<Polygon2> result;
  result.reserve(parts.size());
  for (const auto& loop : parts) result.push_back(without_straight_vertices(ccw, loop));
  return result;
}

}  // namespace rrlab

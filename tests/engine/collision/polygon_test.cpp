#include <rrlab/collision/polygon.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

namespace rrlab {
namespace {

const Polygon2 kUnitSquare{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
// L: a 2 x 1 foot and a 1 x 1 leg on its left end; reflex corner at (1, 1).
const Polygon2 kLPolygon{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
// U: 3 wide, 2 high, a 1 x 1 notch from the top in the middle.
const Polygon2 kUShape{{0, 0}, {3, 0}, {3, 2}, {2, 2}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};

Polygon2 reversed(Polygon2 polygon) {
  std::reverse(polygon.begin(), polygon.end());
  return polygon;
}

// Even-odd ray casting; points on the boundary are not sampled below.
bool contains(const Polygon2& polygon, const Eigen::Vector2d& p) {
  bool inside = false;
  const size_t n = polygon.size();
  for (size_t i = 0, j = n - 1; i < n; j = i++) {
    const auto& a = polygon[i];
    const auto& b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
  }
  return inside;
}

// The parts are convex, counter-clockwise, add up to the area and cover
// exactly the points of the original polygon.
void expect_exact_cover(const Polygon2& polygon, const std::vector<Polygon2>& parts) {
  double area = 0;
  for (const Polygon2& part : parts) {
    EXPECT_TRUE(is_convex(part));
    EXPECT_GT(signed_area(part), 0);
    EXPECT_EQ(polygon_problem(part), "");
    area += signed_area(part);
  }
  EXPECT_NEAR(area, std::abs(signed_area(polygon)), 1e-12);
  // sample on an offset grid so no sample lies on an edge or diagonal
  for (double x = -0.48; x < 3.5; x += 0.0973) {
    for (double y = -0.47; y < 2.5; y += 0.0911) {
      const Eigen::Vector2d p(x, y);
      int covering = 0;
      for (const Polygon2& part : parts) covering += contains(part, p);
      EXPECT_EQ(covering, contains(polygon, p) ? 1 : 0) << "at " << x << ", " << y;
    }
  }
}

TEST(Polygon, SignedAreaFollowsOrientation) {
  EXPECT_DOUBLE_EQ(signed_area(kUnitSquare), 1.0);
  EXPECT_DOUBLE_EQ(signed_area(reversed(kUnitSquare)), -1.0);
  EXPECT_DOUBLE_EQ(signed_area(kLPolygon), 3.0);
  EXPECT_DOUBLE_EQ(signed_area(kUShape), 5.0);
}

TEST(Polygon, Convexity) {
  EXPECT_TRUE(is_convex(kUnitSquare));
  EXPECT_TRUE(is_convex(reversed(kUnitSquare)));
  EXPECT_TRUE(is_convex({{0, 0}, {1, 0}, {2, 0}, {2, 1}}));  // a straight vertex is fine
  EXPECT_FALSE(is_convex(kLPolygon));
  EXPECT_FALSE(is_convex(kUShape));
  EXPECT_FALSE(is_convex({{0, 0}, {1, 1}, {1, 0}, {0, 1}}));  // bow-tie
  // pentagram: every turn is left, yet it winds twice
  Polygon2 star;
  for (int k = 0; k < 5; ++k) {
    const double angle = 2 * std::numbers::pi * (2 * k) / 5;
    star.emplace_back(std::cos(angle), std::sin(angle));
  }
  EXPECT_FALSE(is_convex(star));
}

TEST(Polygon, ConvexInputIsItsOwnDecomposition) {
  const auto parts = convex_decomposition(kUnitSquare);
  ASSERT_EQ(parts.size(), 1u);
  EXPECT_EQ(parts[0], kUnitSquare);
  const auto clockwise = convex_decomposition(reversed(kUnitSquare));
  ASSERT_EQ(clockwise.size(), 1u);
  EXPECT_GT(signed_area(clockwise[0]), 0);  // returned counter-clockwise
}

TEST(Polygon, DecomposesLShape) {
  const auto parts = convex_decomposition(kLPolygon);
  EXPECT_EQ(parts.size(), 2u);  // one reflex vertex: one diagonal suffices
  expect_exact_cover(kLPolygon, parts);
  expect_exact_cover(reversed(kLPolygon), convex_decomposition(reversed(kLPolygon)));
}

TEST(Polygon, DecomposesUShape) {
  const auto parts = convex_decomposition(kUShape);
  EXPECT_GE(parts.size(), 3u);  // two reflex vertices
  EXPECT_LE(parts.size(), 5u);  // Hertel–Mehlhorn: at most 2r + 1 parts for r reflex vertices
  expect_exact_cover(kUShape, parts);
}

TEST(Polygon, DecomposesPolygonWithStraightVertices) {
  // the L with extra vertices in the middle of two edges
  const Polygon2 l_shape{{0, 0}, {1, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}, {0, 1}};
  expect_exact_cover(l_shape, convex_decomposition(l_shape));
}

TEST(Polygon, DecomposesRandomStarShapedPolygons) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> radius(0.3, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    Polygon2 star;
    const int n = 7 + trial;
    for (int k = 0; k < n; ++k) {
      const double angle = 2 * std::numbers::pi * k / n, r = radius(rng);
      star.emplace_back(1.5 + r * std::cos(angle), 1.0 + r * std::sin(angle));
    }
    ASSERT_EQ(polygon_problem(star), "");
    expect_exact_cover(star, convex_decomposition(star));
  }
}

TEST(Polygon, ValidPolygonsHaveNoProblem) {
  EXPECT_EQ(polygon_problem(kUnitSquare), "");
  EXPECT_EQ(polygon_problem(reversed(kLPolygon)), "");
  EXPECT_EQ(polygon_problem(kUShape), "");
}

TEST(Polygon, Problems) {
  EXPECT_EQ(polygon_problem({}), "needs at least 3 points");
  EXPECT_EQ(polygon_problem({{0, 0}, {1, 0}}), "needs at least 3 points");
  EXPECT_EQ(polygon_problem({{0, 0}, {1, 1}, {1, 0}, {0, 1}}), "edges 0 and 2 cross");
  EXPECT_EQ(polygon_problem({{0, 0}, {1, 0}, {2, 0}}), "zero area");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(polygon_problem({{0, 0}, {1, 0}, {nan, 1}}), "non-finite coordinate");
  EXPECT_EQ(polygon_problem({{0, 0}, {1, 0}, {1, 0}, {0, 1}}), "repeated vertex 2");
  // a vertex touching a non-adjacent edge counts as crossing
  EXPECT_EQ(polygon_problem({{0, 0}, {2, 0}, {2, 2}, {1, 0}, {0, 2}}), "edges 0 and 2 cross");
  // a spike folding back along its own edge touches a non-adjacent one
  EXPECT_EQ(polygon_problem({{0, 0}, {2, 0}, {1, 0}, {1, 1}}), "edges 0 and 2 cross");
}

}  // namespace
}  // namespace rrlab

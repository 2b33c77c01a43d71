// Generated meshes: every vertex on the solid's surface, triangles facing out.
#include "support/mesh_shapes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <rrlab/collision/mesh_distance.hpp>

namespace rrlab {
namespace {

using Eigen::Vector3d;

// Every non-degenerate triangle faces away from `inside` (a point of a convex solid).
void expect_outward(const TriangleMesh& mesh, const Vector3d& inside) {
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Vector3d& a = mesh.vertices[size_t(t[0])];
    const Vector3d n = (mesh.vertices[size_t(t[1])] - a).cross(mesh.vertices[size_t(t[2])] - a);
    if (n.norm() < 1e-12) continue;
    EXPECT_GT(n.dot(a - inside), 0.0);
  }
}

TEST(MeshShapes, Box) {
  const TriangleMesh box = box_mesh(Vector3d(1, 2, 3));
  EXPECT_EQ(box.vertices.size(), 8u);
  EXPECT_EQ(box.triangles.size(), 12u);
  for (const Vector3d& v : box.vertices) EXPECT_EQ(v.cwiseAbs(), Vector3d(0.5, 1, 1.5));
  expect_outward(box, Vector3d::Zero());
  EXPECT_TRUE(collision::closed_mesh(box));
}

TEST(MeshShapes, Sphere) {
  const TriangleMesh sphere = sphere_mesh(0.3, 12, 6);
  for (const Vector3d& v : sphere.vertices) EXPECT_NEAR(v.norm(), 0.3, 1e-15);
  expect_outward(sphere, Vector3d::Zero());
  EXPECT_TRUE(collision::closed_mesh(sphere));
}

TEST(MeshShapes, Capsule) {
  constexpr double radius = 0.05, length = 0.4;
  const TriangleMesh capsule = capsule_mesh(radius, length, 16, 4);
  EXPECT_EQ(capsule.vertices.size(), size_t(16 * 2 * (4 + 1)));
  for (const Vector3d& v : capsule.vertices) {
    const Vector3d axis(0, 0, std::clamp(v.z(), 0.0, length));
    EXPECT_NEAR((v - axis).norm(), radius, 1e-15);
  }
  expect_outward(capsule, Vector3d(0, 0, length / 2));
}

}  // namespace
}  // namespace rrlab

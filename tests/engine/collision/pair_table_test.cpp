// The dispatch table: every (backend, link shape, obstacle shape) entry is
// set, and on random poses the analytic entries agree with the FCL reference
// (capsule links) and with the capsule a mesh link tessellates (mesh links).
#include <rrlab/collision/pair_table.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include <rrlab/collision/fcl_pairs.hpp>
#include "support/mesh_shapes.hpp"

namespace rrlab::collision {
namespace {

using Eigen::Vector3d;

constexpr ShapeKind kEveryShape[] = {ShapeKind::polygon, ShapeKind::box,  ShapeKind::sphere,
                                     ShapeKind::point,   ShapeKind::wall, ShapeKind::mesh};

TEST(PairTable, EveryPairHasAFunction) {
  for (DistanceBackend backend : {DistanceBackend::analytic, DistanceBackend::fcl})
    for (LinkShape link : {LinkShape::capsule, LinkShape::mesh})
      for (ShapeKind shape : kEveryShape)
        EXPECT_NE(pair_function(backend, link, shape), nullptr)
            << int(backend) << " " << int(link) << " " << to_string(shape);
  for (ShapeKind shape : kEveryShape) {
    // mesh links are the same in both backends; capsules differ but for walls
    EXPECT_EQ(pair_function(DistanceBackend::analytic, LinkShape::mesh, shape),
              pair_function(DistanceBackend::fcl, LinkShape::mesh, shape));
    EXPECT_EQ(pair_function(DistanceBackend::analytic, LinkShape::capsule, shape) ==
                  pair_function(DistanceBackend::fcl, LinkShape::capsule, shape),
              shape == ShapeKind::wall)
        << to_string(shape);
  }
}

// One obstacle of every kind around the origin, each turned its own way.
struct EveryObstacle {
  std::vector<Obstacle> obstacles;
  std::vector<ObstacleGeometry> geometry;
  std::vector<std::shared_ptr<FclObstacle>> fcl;

  EveryObstacle() {
    auto add = [&](Obstacle o, const Vector3d& position, double angle) {
      o.id = to_string(o.shape);
      o.position0 = o.position = position;
      o.rotation = Eigen::AngleAxisd(angle, Vector3d(1, 2, 3).normalized()).toRotationMatrix();
      obstacles.push_back(o);
    };
    Obstacle polygon;
    polygon.shape = ShapeKind::polygon;
    polygon.points = {{0, 0}, {0.4, 0}, {0.4, 0.2}, {0.2, 0.2}, {0.2, 0.4}, {0, 0.4}};
    polygon.z_min = -0.1;
    polygon.z_max = 0.2;
    add(polygon, Vector3d(0.1, 0.2, 0.0), 0.3);
    Obstacle box;
    box.shape = ShapeKind::box;
    box.size = Vector3d(0.3, 0.2, 0.25);
    add(box, Vector3d(-0.2, 0.1, 0.1), 0.7);
    Obstacle sphere;
    sphere.shape = ShapeKind::sphere;
    sphere.radius = 0.15;
    add(sphere, Vector3d(0.1, -0.2, 0.2), 0.0);
    Obstacle point;
    point.shape = ShapeKind::point;
    add(point, Vector3d(-0.1, -0.1, -0.2), 0.0);
    Obstacle wall;
    wall.shape = ShapeKind::wall;
    wall.normal = Vector3d(0, 0, 1);
    add(wall, Vector3d(0, 0, -0.4), 0.2);
    Obstacle mesh;
    mesh.shape = ShapeKind::mesh;
    mesh.mesh = std::make_shared<TriangleMesh>(sphere_mesh(0.2, 16, 8));
    add(mesh, Vector3d(0.25, -0.25, -0.1), 0.5);
    for (const Obstacle& o : obstacles) {
      geometry.push_back(build_geometry(o));
      geometry.back().rotation = o.rotation;
      geometry.back().position = o.position;
      fcl.push_back(build_fcl(o, geometry.back()));
    }
  }
  PairObstacle at(size_t i) const { return {&geometry[i], fcl[i].get()}; }
};

// Capsules: the analytic entry against the FCL one. Apart, FCL's GJK agrees
// to its tolerance and is never nearer; penetrating, FCL's depth (libccd MPR,
// along its own direction) is never less than the minimum translation.
TEST(PairTable, CapsulesAgreeWithTheFclReference) {
  const EveryObstacle every;
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> coordinate(-0.6, 0.6);
  const std::shared_ptr<FclCapsule> fcl_capsule = make_fcl_capsule(0.0);
  std::vector<int> apart(every.obstacles.size()), penetrating(every.obstacles.size());
  for (int trial = 0; trial < 600; ++trial) {
    PairLink link;
    link.start = Vector3d(coordinate(rng), coordinate(rng), coordinate(rng));
    link.end = Vector3d(coordinate(rng), coordinate(rng), coordinate(rng));
    link.radius = trial % 2 ? 0.03 : 0.0;
    pose_fcl_capsule(*fcl_capsule, link.start, link.end, link.radius);
    link.fcl = fcl_capsule.get();
    for (size_t i = 0; i < every.obstacles.size(); ++i) {
      const ShapeKind shape = every.obstacles[i].shape;
      LinkObstacleDistance ours, theirs;
      pair_function(DistanceBackend::analytic, LinkShape::capsule, shape)(link, every.at(i), ours);
      pair_function(DistanceBackend::fcl, LinkShape::capsule, shape)(link, every.at(i), theirs);
      const std::string where = std::string(to_string(shape)) + " trial " + std::to_string(trial);
      if (ours.distance > 1e-3) {
        EXPECT_LE(ours.distance, theirs.distance + 1e-12) << where;
        EXPECT_NEAR(ours.distance, theirs.distance, 1e-6) << where;
        EXPECT_NEAR((ours.on_link - theirs.on_link).norm(), 0.0, 1e-4) << where;
        ++apart[i];
      } else if (ours.distance < -1e-3 && shape != ShapeKind::mesh) {
        // (a mesh reports contact, not depth, for a segment crossing it)
        EXPECT_GE(ours.distance, theirs.distance - 1e-5) << where;
        ++penetrating[i];
      }
    }
  }
  for (size_t i = 0; i < every.obstacles.size(); ++i) {
    EXPECT_GT(apart[i], 100) << every.obstacles[i].id;
    // (a capsule seldom meets a point; a mesh reports no depth)
    const ShapeKind shape = every.obstacles[i].shape;
    if (shape != ShapeKind::point && shape != ShapeKind::mesh) {
      EXPECT_GT(penetrating[i], 5) << every.obstacles[i].id;
    }
  }
}

// Mesh links: a capsule tessellated (every vertex on its surface, so the mesh
// lies inside it and is never nearer an obstacle) against the same capsule's
// analytic entry, apart.
TEST(PairTable, MeshLinksAgreeWithTheirCapsule) {
  const EveryObstacle every;
  constexpr double radius = 0.04, length = 0.3;
  const TriangleMesh mesh = capsule_mesh(radius, length, 48, 12);
  const std::shared_ptr<MeshBvh> bvh = make_bvh(mesh);
  // the inscribed tessellation lies within the sagitta of its widest facet of
  // the capsule (48 around, caps' rings π/24 apart: a loose bound)
  const double tessellation = radius * (1 - std::cos(M_PI / 48) * std::cos(M_PI / 24));
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> coordinate(-0.6, 0.6), angle(-M_PI, M_PI);
  std::vector<int> compared(every.obstacles.size());
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::AngleAxisd(angle(rng), Vector3d(coordinate(rng), coordinate(rng), 1).normalized())
                        .toRotationMatrix();
    pose.translation() = Vector3d(coordinate(rng), coordinate(rng), coordinate(rng));
    PairLink mesh_link;
    mesh_link.mesh = &mesh;
    mesh_link.bvh = bvh.get();
    mesh_link.pose = &pose;
    PairLink capsule;
    capsule.start = pose * Vector3d::Zero();
    capsule.end = pose * Vector3d(0, 0, length);
    capsule.radius = radius;
    for (size_t i = 0; i < every.obstacles.size(); ++i) {
      const ShapeKind shape = every.obstacles[i].shape;
      LinkObstacleDistance ours, reference;
      pair_function(DistanceBackend::analytic, LinkShape::mesh, shape)(mesh_link, every.at(i), ours);
      pair_function(DistanceBackend::analytic, LinkShape::capsule, shape)(capsule, every.at(i), reference);
      if (reference.distance < 1e-2) continue;
      const std::string where = std::string(to_string(shape)) + " trial " + std::to_string(trial);
      EXPECT_GE(ours.distance, reference.distance - 1e-9) << where;
      // the mesh obstacle is itself a tessellated sphere: both are exact against it
      EXPECT_LE(ours.distance, reference.distance + tessellation + 1e-9) << where;
      EXPECT_NEAR((ours.on_link - ours.on_obstacle).norm(), std::abs(ours.distance), 1e-6) << where;
      ++compared[i];
    }
  }
  for (size_t i = 0; i < every.obstacles.size(); ++i) EXPECT_GT(compared[i], 50) << every.obstacles[i].id;
}

}  // namespace
}  // namespace rrlab::collision

// Link–obstacle distances of a URDF arm (KUKA LBR iiwa 14, scenario 40): the
// analytic capsules against the same capsules as triangle meshes through
// FCL's BVH models, per distance table and per simulator step (dls).
// Mesh resolution: `around` vertices per ring (Arg), 8 rings per cap.
// Mesh obstacles (capsule links against an obstacle's BVH): scenario 40's
// table as its box primitive (Arg 0) and as a 12-triangle box mesh (Arg 1),
// and scenario 43's 576-triangle torus hoop (Arg 2).
#include <benchmark/benchmark.h>

#include <rrlab/collision/collision_world.hpp>
#include <rrlab/collision/mesh_loader.hpp>
#include "support/mesh_shapes.hpp"
#include <rrlab/kinematics/kinematics.hpp>
#include <rrlab/scenario/scenario.hpp>
#include <rrlab/sim/simulator.hpp>

namespace rrlab {
namespace {

Scenario iiwa() { return load_scenario_file(std::string(RRLAB_SOURCE_DIR) + "/scenarios/40_urdf_iiwa14_pose.json"); }

// Every link replaced by its capsule as a mesh, in the frame after its joint.
Scenario iiwa_meshes(int around) {
  Scenario sc = iiwa();
  for (Link& link : sc.model.links) {
    const Eigen::Isometry3d& post = sc.model.joints[size_t(link.last_joint)].post;
    const Eigen::Vector3d start = -(post.linear().transpose() * post.translation());  // segment start, frame after the joint
    const double length = start.norm();
    Eigen::Isometry3d place = Eigen::Isometry3d::Identity();
    place.translation() = start;
    if (length > 0) place.linear() = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), -start).toRotationMatrix();
    auto mesh = std::make_shared<TriangleMesh>();
    mesh->append(capsule_mesh(link.radius, length, around), place);
    link.mesh = mesh;
  }
  return sc;
}

// The distance table at q0, by `compute` (rrlab's) or `compute_with_fcl` (FCL's own queries).
void distances(benchmark::State& state, const Scenario& sc,
               void (CollisionWorld::*compute)(const KinematicsData&, DistanceTable&) = &CollisionWorld::compute) {
  CollisionWorld world(sc.model, sc.scene);
  KinematicsData kin(sc.model);
  DistanceTable table;
  forward_kinematics(sc.model, sc.q0, kin);
  for (auto _ : state) {
    (world.*compute)(kin, table);
    benchmark::DoNotOptimize(table.min_distance);
  }
  state.counters["min_link"] = benchmark::Counter(table.min_link);
}

void BM_urdf_capsule_distances(benchmark::State& state) { distances(state, iiwa()); }
void BM_urdf_mesh_distances(benchmark::State& state) {
  distances(state, iiwa_meshes(int(state.range(0))));
  state.counters["triangles_per_link"] = double(2 * (2 * 8 + 1) * state.range(0));
}

void steps(benchmark::State& state, const Scenario& sc) {
  Simulator sim(sc, "dls");
  for (auto _ : state) {
    if (sim.done()) sim.reset();
    sim.step();
  }
}
void BM_urdf_capsule_step(benchmark::State& state) { steps(state, iiwa()); }
void BM_urdf_mesh_step(benchmark::State& state) { steps(state, iiwa_meshes(int(state.range(0)))); }

// Scenario 40 with the table as a box primitive (0) or as the same box as a mesh (1); scenario 43 (2).
Scenario mesh_obstacle_case(int which) {
  if (which == 2)
    return load_scenario_file(std::string(RRLAB_SOURCE_DIR) + "/scenarios/43_urdf_iiwa14_mesh_obstacle.json");
  Scenario sc = iiwa();
  if (which == 1) {
    Obstacle& table = sc.scene.obstacles[size_t(sc.scene.find("table"))];
    table.shape = ShapeKind::mesh;
    table.mesh = std::make_shared<TriangleMesh>(box_mesh(table.size));
  }
  return sc;
}
void BM_mesh_obstacle_distances(benchmark::State& state) { distances(state, mesh_obstacle_case(int(state.range(0)))); }
// The same tables from FCL's own queries (compute_with_fcl: fcl::distance of
// each capsule against the BVHModel, GJK per triangle), for comparison.
void BM_mesh_obstacle_fcl_distances(benchmark::State& state) {
  distances(state, mesh_obstacle_case(int(state.range(0))), &CollisionWorld::compute_with_fcl);
}
void BM_mesh_obstacle_step(benchmark::State& state) { steps(state, mesh_obstacle_case(int(state.range(0)))); }

BENCHMARK(BM_urdf_capsule_distances);
BENCHMARK(BM_mesh_obstacle_distances)->Arg(0)->Arg(1)->Arg(2);
BENCHMARK(BM_mesh_obstacle_fcl_distances)->Arg(0)->Arg(1)->Arg(2);
BENCHMARK(BM_mesh_obstacle_step)->Arg(0)->Arg(1)->Arg(2);
BENCHMARK(BM_urdf_mesh_distances)->Arg(16)->Arg(64);
BENCHMARK(BM_urdf_capsule_step);
BENCHMARK(BM_urdf_mesh_step)->Arg(16)->Arg(64);

}  // namespace
}  // namespace rrlab

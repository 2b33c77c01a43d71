// Link–obstacle distances of a URDF arm (KUKA LBR iiwa 14, scenario 40): the
// analytic capsules against the same capsules as triangle meshes through
// FCL's BVH models, per distance table and per simulator step (dls).
// Mesh resolution: `around` vertices per ring (Arg), 8 rings per cap.
#include <benchmark/benchmark.h>

#include "collision/collision_world.hpp"
#include "collision/mesh_loader.hpp"
#include "kinematics/kinematics.hpp"
#include "scenario/scenario.hpp"
#include "sim/simulator.hpp"

namespace rrlab {
namespace {

// A capsule of `radius` around the z segment [0, length], vertices on its surface.
TriangleMesh capsule_mesh(double radius, double length, int around, int rings = 8) {
  TriangleMesh m;
  std::vector<std::pair<double, double>> profile;
  for (int i = 0; i <= rings; ++i) {
    const double a = -M_PI / 2 + M_PI / 2 * i / rings;
    profile.emplace_back(radius * std::cos(a), radius * std::sin(a));
  }
  for (int i = 0; i <= rings; ++i) {
    const double a = M_PI / 2 * i / rings;
    profile.emplace_back(radius * std::cos(a), length + radius * std::sin(a));
  }
  for (const auto& [r, z] : profile)
    for (int k = 0; k < around; ++k)
      m.vertices.emplace_back(r * std::cos(2 * M_PI * k / around), r * std::sin(2 * M_PI * k / around), z);
  const int n = int(profile.size());
  for (int i = 0; i + 1 < n; ++i)
    for (int k = 0; k < around; ++k) {
      const int a = i * around + k, b = i * around + (k + 1) % around;
      m.triangles.emplace_back(a, b, b + around);
      m.triangles.emplace_back(a, b + around, a + around);
    }
  return m;
}

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

void distances(benchmark::State& state, const Scenario& sc) {
  CollisionWorld world(sc.model, sc.scene);
  KinematicsData kin(sc.model);
  DistanceTable table;
  forward_kinematics(sc.model, sc.q0, kin);
  for (auto _ : state) {
    world.compute(kin, table);
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

BENCHMARK(BM_urdf_capsule_distances);
BENCHMARK(BM_urdf_mesh_distances)->Arg(16)->Arg(64);
BENCHMARK(BM_urdf_capsule_step);
BENCHMARK(BM_urdf_mesh_step)->Arg(16)->Arg(64);

}  // namespace
}  // namespace rrlab

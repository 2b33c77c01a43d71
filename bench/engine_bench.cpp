// Engine step costs on a 7-DOF DH arm (KUKA iiwa-like), next to Orocos KDL's
// solvers on the same chain in the same process. Solvers and workspaces are
// built once, outside the timed loops, for both.
#include <benchmark/benchmark.h>

#include <kdl/chain.hpp>
#include <kdl/chainiksolvervel_pinv.hpp>
#include <kdl/chainiksolvervel_wdls.hpp>
#include <kdl/chainjnttojacsolver.hpp>

#include <rrlab/collision/collision_world.hpp>
#include <rrlab/collision/self_collision.hpp>
#include <rrlab/kinematics/kinematics.hpp>
#include <rrlab/methods/registry.hpp>
#include <rrlab/scenario/scenario.hpp>
#include <rrlab/sim/simulator.hpp>

namespace rrlab {
namespace {

const double kHalfPi = M_PI / 2;
const std::vector<DhLinkSpec> kIiwa = {{0, -kHalfPi, 0.36, 0, 0.06}, {0, kHalfPi, 0, 0, 0.06},
                                       {0, kHalfPi, 0.42, 0, 0.06},  {0, -kHalfPi, 0, 0, 0.06},
                                       {0, -kHalfPi, 0.40, 0, 0.05}, {0, kHalfPi, 0, 0, 0.05},
                                       {0, 0, 0.126, 0, 0.04}};

Eigen::VectorXd start_q() {
  Eigen::VectorXd q(7);
  q << 0.1, 0.7, -0.2, -1.2, 0.3, 1.0, 0.2;
  return q;
}

Eigen::VectorXd task_velocity() {
  Eigen::VectorXd xdot(6);
  xdot << 0.1, -0.05, 0.02, 0.1, 0.05, -0.1;
  return xdot;
}

KDL::Chain kdl_chain() {
  KDL::Chain chain;
  for (const DhLinkSpec& l : kIiwa)
    chain.addSegment(KDL::Segment(KDL::Joint(KDL::Joint::RotZ), KDL::Frame::DH(l.a, l.alpha, l.d, l.theta)));
  return chain;
}

// A small wiggle so no iteration sees exactly the previous input.
void wiggle(Eigen::VectorXd& q, long i) { q[0] = 0.1 + 1e-6 * double(i & 1023); }

void BM_rrlab_fk_jacobian(benchmark::State& state) {
  const Model model = make_dh(kIiwa, Eigen::Isometry3d::Identity());
  KinematicsData kin(model);
  Eigen::MatrixXd jac(6, 7);
  Eigen::VectorXd q = start_q();
  long i = 0;
  for (auto _ : state) {
    wiggle(q, i++);
    forward_kinematics(model, q, kin);
    task_jacobian(model, kin, TaskSpace::pose, jac);
    benchmark::DoNotOptimize(jac.data());
  }
}
BENCHMARK(BM_rrlab_fk_jacobian);

void BM_kdl_fk_jacobian(benchmark::State& state) {
  const KDL::Chain chain = kdl_chain();
  KDL::ChainJntToJacSolver solver(chain);
  KDL::JntArray q(7);
  q.data = start_q();
  KDL::Jacobian jac(7);
  long i = 0;
  for (auto _ : state) {
    wiggle(q.data, i++);
    solver.JntToJac(q, jac);
    benchmark::DoNotOptimize(jac.data.data());
  }
}
BENCHMARK(BM_kdl_fk_jacobian);

// Full method step: kinematics and Jacobian from q, then the method's solve.
void method_step(benchmark::State& state, const char* name) {
  const Model model = make_dh(kIiwa, Eigen::Isometry3d::Identity());
  KinematicsData kin(model);
  Eigen::MatrixXd jac(6, 7);
  Scene scene;
  DistanceTable distances;
  distances.resize(model.link_count(), 0);
  const SelfDistanceTable self_distances;  // no self pairs checked here, as no obstacles
  TaskRef ref(TaskSpace::pose);
  ref.xdot = task_velocity();
  State s;
  s.q = start_q();
  s.qdot = Eigen::VectorXd::Zero(7);
  auto method = find_method(name)->make({model, TaskSpace::pose, 0});
  TaskSpec task_spec;
  task_spec.space = TaskSpace::pose;
  task_spec.trajectory.type = TrajectoryType::joystick;
  const Task task(task_spec, Eigen::Isometry3d::Identity(), 1.0, 0.001);
  StepOutput out;
  out.qdot = Eigen::VectorXd::Zero(7);
  out.diag.values = Eigen::VectorXd::Zero(Eigen::Index(method->diagnostic_names().size()));
  long i = 0;
  for (auto _ : state) {
    wiggle(s.q, i++);
    forward_kinematics(model, s.q, kin);
    task_jacobian(model, kin, TaskSpace::pose, jac);
    const StepInput in{model, s, ref, scene, 0.001, kin, jac, distances, task, self_distances};
    method->step(in, out);
    benchmark::DoNotOptimize(out.qdot.data());
  }
}
void BM_rrlab_pinv_step(benchmark::State& state) { method_step(state, "pinv"); }
void BM_rrlab_dls_step(benchmark::State& state) { method_step(state, "dls"); }
void BM_rrlab_sr_task_priority_step(benchmark::State& state) { method_step(state, "sr_task_priority"); }
BENCHMARK(BM_rrlab_pinv_step);
BENCHMARK(BM_rrlab_dls_step);
BENCHMARK(BM_rrlab_sr_task_priority_step);

// KDL's velocity IK solvers compute the Jacobian from q inside CartToJnt.
template <class Solver>
void kdl_ik_step(benchmark::State& state, Solver& solver) {
  KDL::JntArray q(7), qdot(7);
  q.data = start_q();
  const Eigen::VectorXd xdot = task_velocity();
  const KDL::Twist twist(KDL::Vector(xdot[0], xdot[1], xdot[2]), KDL::Vector(xdot[3], xdot[4], xdot[5]));
  long i = 0;
  for (auto _ : state) {
    wiggle(q.data, i++);
    solver.CartToJnt(q, twist, qdot);
    benchmark::DoNotOptimize(qdot.data.data());
  }
}

void BM_kdl_pinv_step(benchmark::State& state) {
  const KDL::Chain chain = kdl_chain();
  KDL::ChainIkSolverVel_pinv solver(chain);
  kdl_ik_step(state, solver);
}
void BM_kdl_wdls_step(benchmark::State& state) {
  const KDL::Chain chain = kdl_chain();
  KDL::ChainIkSolverVel_wdls solver(chain);
  solver.setLambda(0.05);
  kdl_ik_step(state, solver);
}
BENCHMARK(BM_kdl_pinv_step);
BENCHMARK(BM_kdl_wdls_step);

// A whole simulator step of the demo scenarios (kinematics, distances to every
// obstacle, reference, method, metrics, integration).
void sim_step(benchmark::State& state, const std::string& file) {
  Simulator sim(load_scenario_file(std::string(RRLAB_SOURCE_DIR) + "/scenarios/" + file));
  for (auto _ : state) {
    if (sim.done()) sim.reset();
    sim.step();
  }
}
void BM_rrlab_sim_step_planar7(benchmark::State& state) { sim_step(state, "01_planar7_obstacles.json"); }
void BM_rrlab_sim_step_dh7_pose(benchmark::State& state) { sim_step(state, "03_dh7_pose.json"); }
BENCHMARK(BM_rrlab_sim_step_planar7);
BENCHMARK(BM_rrlab_sim_step_dh7_pose);

// The self-collision part of a step: every pair the robot's allowed-collision
// matrix keeps, at the scenario's start (planar 7 links: 15 pairs; the 12-link
// Chen arm: 55; the iiwa14 URDF capsules: 14).
void self_distances(benchmark::State& state, const std::string& file) {
  const Scenario scenario = load_scenario_file(std::string(RRLAB_SOURCE_DIR) + "/scenarios/" + file);
  KinematicsData kin(scenario.model);
  forward_kinematics(scenario.model, scenario.q0, kin);
  SelfCollisionWorld world(scenario.model);
  SelfDistanceTable table;
  for (auto _ : state) {
    world.compute(kin, table);
    benchmark::DoNotOptimize(table.min_distance);
  }
  state.counters["pairs"] = double(table.pairs.size());
}
void BM_rrlab_self_distances_planar7(benchmark::State& state) { self_distances(state, "01_planar7_obstacles.json"); }
void BM_rrlab_self_distances_planar12(benchmark::State& state) { self_distances(state, "16_chen_sim1_planar12.json"); }
void BM_rrlab_self_distances_iiwa14(benchmark::State& state) { self_distances(state, "40_urdf_iiwa14_pose.json"); }
BENCHMARK(BM_rrlab_self_distances_planar7);
BENCHMARK(BM_rrlab_self_distances_planar12);
BENCHMARK(BM_rrlab_self_distances_iiwa14);

}  // namespace
}  // namespace rrlab

// The hard constraints of the differential-IK baselines (qp_ik, hqp, diffik)
// on the joint velocity q̇ of one step: joint limits as a box, and velocity
// dampers (Faverjon & Tournassoud 1987) on every link–obstacle pair and every
// self pair within the detection distance, as rows A q̇ ≥ b. Built once per
// step into preallocated storage; the three methods differ only in what they
// optimise over this set.
#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

#include <rrlab/methods/method.hpp>
#include <rrlab/util/qp_solver.hpp>

namespace rrlab {

// Joint limits as bounds on q̇ (docs/methods.md, "Constraints of qp_ik, hqp and diffik").
struct LimitSettings {
  double position_gain = 0.5;  // γ of (q_min − q)/dt·γ ≤ q̇ ≤ (q_max − q)/dt·γ
  double max_step = 0.02;      // m: no joint alone moves a point of the arm farther in one step (0: off)
};

// Velocity dampers: ḋ ≥ −ξ (d − d_s)/(d_i − d_s) for each pair with d < d_i.
struct DamperSettings {
  double detection = 0.1;  // d_i, m
  double safety = 0.01;    // d_s, m
  double gain = 0.5;       // ξ, m/s
  bool self_pairs = true;  // also the model's self pairs
};

// What one damper row keeps apart: a link and an obstacle (other = −1 − obstacle
// index) or two links; the two nearest points, for the dashboard's segment.
struct DamperPair {
  int link = 0, other = 0;
  Eigen::Vector3d on_link = Eigen::Vector3d::Zero(), on_other = Eigen::Vector3d::Zero();
  double distance = 0;
};

struct VelocityConstraints {
  Eigen::VectorXd lower, upper;  // the box on q̇, never empty
  Eigen::MatrixXd A;             // rows × n (capacity rows)
  Eigen::VectorXd b;
  int rows = 0;
  std::vector<DamperPair> pairs;  // one per row
};

// R_i: the farthest capsule point moved by joint i from its axis (revolute),
// 1 for a prismatic joint (every point moves by the joint's own displacement).
// `reach` has one entry per joint. (qp_constraints' step cap uses it too.)
void joint_reach(const Model& model, const KinematicsData& kin, Eigen::VectorXd& reach);

// An obstacle shape with flat faces (box, polygon, wall, mesh): a link nearly
// parallel to a face has two near points, so rows go at the link's ends too.
// (qp_constraints' rows use it too.)
inline bool has_faces(ShapeKind shape) {
  return shape == ShapeKind::box || shape == ShapeKind::polygon || shape == ShapeKind::wall || shape == ShapeKind::mesh;
}

// The largest velocity towards a limit `room` (> 0) away that one step of it
// and then braking at `acc` (finite) keeps inside: v²/(2a) + 1.5 v dt = room,
// the step plus the braking distance of the discrete deceleration v, v − a dt, …
// (qp_constraints' bounds use it too.)
double braking_velocity(double room, double acc, double dt);

class VelocityConstraintBuilder {
 public:
  VelocityConstraintBuilder(const Model& model, int obstacle_count);

  // Rows the builder may write (links × obstacles × 3 + self pairs).
  int capacity() const { return capacity_; }
  // True when the scene outgrew the capacity (obstacles added): the caller
  // resizes its problems after calling resize(), which allocates once.
  bool needs_resize(const StepInput& in) const;
  void resize(const Model& model, int obstacle_count);

  // The box and the damper rows at this step into `out` (sized by capacity).
  void build(const StepInput& in, const LimitSettings& limits, const DamperSettings& dampers,
             VelocityConstraints& out);
  void size(VelocityConstraints& out) const;

 private:
  void joint_bounds(const StepInput& in, const LimitSettings& limits, VelocityConstraints& out);
  void obstacle_rows(const StepInput& in, const DamperSettings& dampers, VelocityConstraints& out);
  void self_rows(const StepInput& in, const DamperSettings& dampers, VelocityConstraints& out);
  // one row n_rowᵀ (J_p q̇) − v_along ≥ −ξ (d − d_s)/(d_i − d_s), clamped to one step (see .cpp)
  void add_row(const StepInput& in, const DamperSettings& dampers, double distance, VelocityConstraints& out);

  int n_, capacity_ = 0;
  Eigen::MatrixXd point_jacobian_, other_jacobian_;
  Eigen::VectorXd reach_;
};

// The least violation of the damper rows that the box allows (level 1 of the
// hierarchy; Kanoun, Lamiraux & Wieber 2011): min ½‖w‖² + ½ε‖q̇‖² over
// x = [q̇; w] subject to A q̇ + w ≥ b, w ≥ 0, lower ≤ q̇ ≤ upper. Always
// feasible (the box is never empty); the caller then asks A q̇ ≥ b − w*.
class LeastViolation {
 public:
  LeastViolation(int dof, int row_capacity);
  // Returns the optimal slack per row in `slack` (size ≥ rows); false if the
  // solver failed (not expected), with slack = max(b − A q̇₀, 0) at q̇₀ = box ∩ 0.
  bool solve(const VelocityConstraints& constraints, Eigen::VectorXd& slack);
  const Eigen::VectorXd& qdot() const { return qdot_; }

 private:
  int n_, capacity_;
  QpProblem problem_;
  QpSolver solver_;
  Eigen::VectorXd qdot_;
};

// Damper rows active at a solution (row k of the solver's inequalities at
// first_row + k), drawn as segments between the pair's nearest points.
// `segments` keeps its capacity (reserve it once).
int draw_active_dampers(const QpSolver& solver, int first_row, const VelocityConstraints& constraints,
                        std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& segments);

}  // namespace rrlab

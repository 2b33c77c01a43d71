// Kapoor, Cetin & Tesar (1998) §3.2: the criteria by which a direct-search
// step selects among its options (the method is direct_search.cpp), each
// minimised:
//  ψ1 JRA = Σ (θ_i − θ'_i)²/θ_i,max, θ'_i mid-range. The paper is silent on
//     θ_i,max: here the joint's half range (the displacement from mid-range
//     to the limit); joints without both limits do not count in JRA.
//  ψ2 JVM = Σ (θ_i − θ_i,curr)².
//  ψ3 DM = σmax/σmin of the task Jacobian. DM mixes lengths and angles: its
//     value depends on the length unit of the position rows, which the paper
//     does not give. Here the position rows are divided by a stated
//     characteristic length L (`dm_length`, m), so DM values are comparable
//     only at the same L and robot, never with the paper's numbers.
//  ψ4 (not in the paper) the engine's obstacle clearance −min_link d_link,
//     from the first-order change of each link's distance to its nearest
//     obstacle, d + nᵀJ_p(θ − θ_curr), over the step's distance table (exact
//     to O(Δ²); no collision query per option).
#pragma once

#include <Eigen/Core>

#include <rrlab/kinematics/kinematics.hpp>
#include <rrlab/methods/method.hpp>
#include <rrlab/util/extreme_eigenvalues.hpp>

namespace rrlab::kapoor {

// Columns of the options' criteria table.
enum Criterion { kJra, kJvm, kDm, kObstacle, kCriteria };

class Criteria {
 public:
  Criteria(const Model& model, TaskSpace space);

  // ψ1 at θ.
  double joint_range(const Eigen::VectorXd& theta) const { return (theta - centre_).cwiseAbs2().dot(inv_half_range_); }
  // ψ2 at θ from the current q.
  static double joint_velocity(const Eigen::VectorXd& theta, const Eigen::VectorXd& q) {
    return (theta - q).squaredNorm();
  }
  // ψ3 = σmax/σmin of the task Jacobian, the position rows of a pose task
  // divided by the characteristic length L (`length`).
  double dexterity(const Eigen::MatrixXd& jacobian, double length);

  // ψ4's first-order rows nᵀJ_p of each link's nearest obstacle pair, from
  // the step's distance table at the current configuration.
  void prepare_clearance(const StepInput& in);
  bool has_distances() const { return has_distances_; }
  // min over links of d + nᵀJ_p(θ − q); 0 (constant) without obstacles.
  double estimated_clearance(const Eigen::VectorXd& theta, const Eigen::VectorXd& q);

 private:
  template <int M>
  void gram(const Eigen::MatrixXd& jacobian, double length);

  int n_, m_;
  Eigen::VectorXd centre_, inv_half_range_;
  ExtremeEigenvalues::Matrix jjt_;  // at most 6 x 6 (pose), fixed capacity
  ExtremeEigenvalues eigenvalues_;
  Eigen::MatrixXd distance_rows_;
  Eigen::VectorXd distances_now_, delta_theta_;
  Eigen::MatrixXd point_jacobian_;
  int links_with_distance_ = 0;
  bool has_distances_ = false;
};

}  // namespace rrlab::kapoor

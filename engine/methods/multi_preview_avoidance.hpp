// Zhang et al. avoidance manipulability: avoidance matrices of the
// intermediate link points, their (complete or partial) ellipsoids, the
// avoidance manipulability shape index AMSI and, with an obstacle potential,
// AMSIP. Used by the multi_preview method for the actual arm and for every
// imaginary manipulator its GA evaluates; allocation-free after construction.
#pragma once

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <vector>

#include <rrlab/collision/collision_world.hpp>
#include <rrlab/kinematics/kinematics.hpp>
#include <rrlab/model/model.hpp>
#include <rrlab/util/right_inverse.hpp>

namespace rrlab {

// Zhang eq. 19: c_r, the volume of the unit ball in r dimensions
// (2, π, 4π/3, … for r = 1, 2, 3); c_0 = 1.
double unit_ball_volume(int r);

// One link point's avoidance manipulability ellipsoid ¹P_i (eq. 8 / 11): the
// image of ‖¹l‖ ≤ 1 under ¹M_i, with semi-axes σ_k u_k.
struct AvoidanceEllipsoid {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();      // the link point (world)
  Eigen::Vector3d sigma = Eigen::Vector3d::Zero();       // singular values of ¹M_i, descending (0-padded)
  Eigen::Matrix3d directions = Eigen::Matrix3d::Zero();  // columns u_k (world, unit) for sigma[k]; zero without directions
  int rank = 0;        // numerical rank: < m is a partial ellipsoid (eq. 11)
  int volume_rank = 0;  // generic rank r_i of the point: the dimension V_i is measured in
  double volume = 0;   // ¹V_i = c_r · σ_1 ⋯ σ_r (eq. 18, 20)
};

class AvoidanceManipulability {
 public:
  // Link points are the tips of every link but the last (the paper's
  // intermediate links i = 1..n−1); m = 2 rows for planar models, else 3.
  // Without `directions` (the GA's imaginary manipulators score AMSI only)
  // an ellipsoid keeps its centre and volume but neither semi-axes nor rank:
  // the volumes come from ¹M_i ¹M_iᵀ's principal minors, without an
  // eigen-decomposition (the same volumes to rounding, ~1e-15 relative).
  AvoidanceManipulability(const Model& model, TaskSpace space, bool directions = true);

  // Avoidance matrices and ellipsoids at a configuration whose kinematics and
  // task (hand) Jacobian J_n are given; returns AMSI ¹E (eq. 21).
  double compute(const Model& model, const KinematicsData& kin, const Eigen::MatrixXd& hand_jacobian);

  int point_count() const { return static_cast<int>(ellipsoids_.size()); }
  int rows() const { return rows_; }
  double amsi() const { return amsi_; }
  const AvoidanceEllipsoid& ellipsoid(int i) const { return ellipsoids_[i]; }
  const Eigen::MatrixXd& avoidance_matrix(int i) const { return matrices_[i]; }  // ¹M_i, rows() x n
  const Eigen::MatrixXd& point_jacobian(int i) const { return point_jacobians_[i]; }  // J_i, rows() x n
  const Eigen::MatrixXd& null_projector() const { return null_projector_; }  // I − J_n⁺J_n

 private:
  void decompose(int i);
  double compute_volumes(const Model& model, const KinematicsData& kin);  // without directions

  int n_, rows_;
  bool directions_;
  RightInverse hand_inverse_;
  Eigen::MatrixXd null_projector_, jacobian3_;
  Eigen::VectorXd unit_, column_;
  std::vector<Eigen::MatrixXd> point_jacobians_, matrices_;
  std::vector<AvoidanceEllipsoid> ellipsoids_;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig_;
  double amsi_ = 0;
  double ball_volume_[4] = {};  // c_r of eq. 19 for r = 0..3
};

// Zhang eq. 12–17, plural avoidance tasks: after avoidance tasks were realised
// at the link points `realised` (in priority order), the next avoidance matrix
// of point j is J_j (I − J_n⁺J_n) Π_k (I − ᵏM⁺ ᵏM), where ᵏM is the avoidance
// matrix of the k-th realised point in its own turn (eq. 15 for the second
// task, eq. 17 for the third). An analysis tool (allocates): `point_jacobians`
// are the J_i of every point, `hand_jacobian` J_n; returns one matrix per point
// (those of realised points are zero: eq. 15 gives ²M_i = 0).
std::vector<Eigen::MatrixXd> plural_avoidance_matrices(const std::vector<Eigen::MatrixXd>& point_jacobians,
                                                       const Eigen::MatrixXd& hand_jacobian,
                                                       const std::vector<int>& realised);

// AMSIP's potential U ≤ 0 (eq. 22), our choice where the paper refers to [8]:
// a band of `width` w around every obstacle surface, depth `height` h,
//   U = −h Σ_links Σ_obstacles max(0, 1 − d/w)²,
// d the signed link-capsule distance. U = 0 outside the bands, −h per link
// touching an obstacle, and it keeps falling (quadratically) with penetration,
// so ¹S = ¹E + U < 0 at a collision whenever h exceeds the arm's largest AMSI.
double obstacle_potential(const DistanceTable& distances, double width, double height);

}  // namespace rrlab

// Right inverses of a wide k x n matrix A (k <= n), allocation-free after
// construction: Whitney's pseudoinverse A⁺ = Aᵀ(AAᵀ)⁺ and Wampler's damped
// least squares A* = Aᵀ(AAᵀ + λ²I)⁻¹. Factor once, apply to many vectors.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>

namespace rrlab {

class RightInverse {
 public:
  RightInverse(int rows, int cols);

  // A⁺ through the eigen-decomposition of AAᵀ = UΛUᵀ; directions with
  // σ² < rel_tol·σmax² are dropped (a rank-deficient A gets its true pseudoinverse).
  void factor_pinv(const Eigen::MatrixXd& a, double rel_tol = 1e-12);
  // A* = Aᵀ(AAᵀ + λ²I)⁻¹ through a Cholesky factorisation.
  void factor_dls(const Eigen::MatrixXd& a, double lambda);

  // x = A^# y for the last factorisation.
  void apply(const Eigen::VectorXd& y, Eigen::VectorXd& x);
  // out = (I − A^# A) z: the component of z that A does not see (exactly so
  // after factor_pinv; approximately after factor_dls).
  void null_project(const Eigen::VectorXd& z, Eigen::VectorXd& out);

  int rows() const { return static_cast<int>(a_.rows()); }
  int cols() const { return static_cast<int>(a_.cols()); }
  // Singular values from the last factor_pinv (descending order not kept).
  double sigma_min() const { return sigma_min_; }
  double sigma_max() const { return sigma_max_; }

 private:
  Eigen::MatrixXd a_, aat_;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig_;
  Eigen::LLT<Eigen::MatrixXd> llt_;
  Eigen::VectorXd inv_eigenvalues_, tmp_k_, tmp_k2_;
  bool damped_ = false;
  double sigma_min_ = 0, sigma_max_ = 0;
};

}  // namespace rrlab

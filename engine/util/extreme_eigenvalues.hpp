// The smallest and largest eigenvalue of a symmetric matrix of at most 6 x 6
// (a task's J Jᵀ), without the other eigenvalues: Householder
// tridiagonalisation, then Laguerre's method on the characteristic
// polynomial det(T − xI) from outside the spectrum, both ends in one loop.
// For a polynomial whose roots are all real, Laguerre from above the
// largest root (from below the smallest) falls monotonically onto it, so
// every iterate stays a bound; it stops at a step below 1e-5 of the iterate
// (cubic convergence leaves about its cube). Sturm counts then confirm each
// end to a few ε of the matrix's scale, the accuracy QR has; an end they do
// not confirm iterates on until rounding stops the steps. Where that
// fails (a cluster of nearly equal extreme eigenvalues, which p(x) resolves
// only to √ε) or the iteration does not settle, the full QR eigensolver
// gives the answer.
// Allocation-free after construction.
#pragma once

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

namespace rrlab {

class ExtremeEigenvalues {
 public:
  using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;

  explicit ExtremeEigenvalues(int size);

  // Eigenvalues of the symmetric `a` (its lower triangle is read); size ≤ 6.
  void compute(const Matrix& a);
  double min() const { return min_; }
  double max() const { return max_; }
  // Laguerre iterations of the last compute (both ends), or −1 when the QR fallback answered.
  int iterations() const { return iterations_; }

 private:
  Eigen::SelfAdjointEigenSolver<Matrix> fallback_;
  double min_ = 0, max_ = 0;
  int iterations_ = 0;
};

}  // namespace rrlab

// LU factorisation with partial pivoting of a square matrix of at most 6 x 6
// (a task-sized block), on the stack: Gaussian elimination, the pivot the
// largest magnitude in its column. Several times faster than Eigen's
// PartialPivLU at these sizes, where Eigen's general blocked code dominates.
// A singular matrix is factored all the same: a zero pivot column is left
// as it is (as PartialPivLU does), determinant() is then 0 and solve()
// returns non-finite values.
#pragma once

#include <Eigen/Core>
#include <cassert>
#include <cmath>
#include <utility>

namespace rrlab {

class SmallLu {
 public:
  static constexpr int kMax = 6;

  // Factors the n x n matrix a (n ≤ 6).
  template <typename Matrix>
  void compute(const Matrix& a) {
    n_ = int(a.rows());
    assert(n_ <= kMax && a.cols() == n_);
    for (int r = 0; r < n_; ++r)
      for (int c = 0; c < n_; ++c) lu_[r][c] = a(r, c);
    factor();
  }

  // Factors the square matrix of a's columns cols[0..rows − 1] (a block of a
  // Jacobian, without copying it out first).
  template <typename Matrix>
  void compute_columns(const Matrix& a, const int* cols) {
    n_ = int(a.rows());
    assert(n_ <= kMax);
    for (int c = 0; c < n_; ++c)
      for (int r = 0; r < n_; ++r) lu_[r][c] = a(r, cols[c]);
    factor();
  }

  // x = A⁻¹ b (x and b may be the same vector).
  template <typename In, typename Out>
  void solve(const In& b, Out& x) const {
    double y[kMax];
    for (int r = 0; r < n_; ++r) y[r] = b[order_[r]];  // P b
    switch (n_) {
      case 1: substitute<1>(y); break;
      case 2: substitute<2>(y); break;
      case 3: substitute<3>(y); break;
      case 4: substitute<4>(y); break;
      case 5: substitute<5>(y); break;
      case 6: substitute<6>(y); break;
    }
    for (int r = 0; r < n_; ++r) x[r] = y[r];
  }

  double determinant() const {
    double d = sign_;
    for (int k = 0; k < n_; ++k) d *= lu_[k][k];
    return d;
  }

 private:
  void factor() {
    switch (n_) {  // fixed sizes unroll: the same operations in the same order
      case 1: factor<1>(); break;
      case 2: factor<2>(); break;
      case 3: factor<3>(); break;
      case 4: factor<4>(); break;
      case 5: factor<5>(); break;
      case 6: factor<6>(); break;
    }
  }

  // Gaussian elimination with partial pivoting on lu_ (N x N).
  template <int N>
  void factor() {
    sign_ = 1;
    for (int k = 0; k < N; ++k) order_[k] = k;
    for (int k = 0; k < N; ++k) {
      int pivot = k;
      for (int r = k + 1; r < N; ++r)
        if (std::abs(lu_[r][k]) > std::abs(lu_[pivot][k])) pivot = r;
      if (pivot != k) {
        std::swap(lu_[k], lu_[pivot]);
        std::swap(order_[k], order_[pivot]);
        sign_ = -sign_;
      }
      const double inverse = 1.0 / lu_[k][k];
      inverse_diagonal_[k] = inverse;  // ±inf for a zero pivot, as a division by it gives
      if (lu_[k][k] == 0) continue;  // nothing to eliminate with: a singular matrix
      for (int r = k + 1; r < N; ++r) {
        const double l = lu_[r][k] * inverse;
        lu_[r][k] = l;
        for (int c = k + 1; c < N; ++c) lu_[r][c] -= l * lu_[k][c];
      }
    }
  }

  // y ← A⁻¹ y for y = P b: L y = P b (unit diagonal), U x = y. The back
  // substitution multiplies by the pivots' reciprocals: a division on each
  // link of its dependent chain would cost several times more.
  template <int N>
  void substitute(double* y) const {
    for (int r = 1; r < N; ++r)
      for (int c = 0; c < r; ++c) y[r] -= lu_[r][c] * y[c];
    for (int r = N - 1; r >= 0; --r) {
      for (int c = r + 1; c < N; ++c) y[r] -= lu_[r][c] * y[c];
      y[r] *= inverse_diagonal_[r];
    }
  }

  double lu_[kMax][kMax] = {};
  double inverse_diagonal_[kMax] = {};
  int order_[kMax] = {};  // row r of P A is row order_[r] of A
  int n_ = 0;
  double sign_ = 1;
};

}  // namespace rrlab

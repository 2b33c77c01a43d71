#include <rrlab/util/right_inverse.hpp>

#include <algorithm>
#include <cassert>
#include <cmath>

namespace rrlab {

RightInverse::RightInverse(int rows, int cols)
    : a_(rows, cols),
      aat_(rows, rows),
      eig_(rows),
      llt_(rows),
      inv_eigenvalues_(rows),
      tmp_k_(rows),
      tmp_k2_(rows) {}

void RightInverse::factor_pinv(const Eigen::MatrixXd& a, double rel_tol) {
  assert(a.rows() == a_.rows() && a.cols() == a_.cols());
  a_ = a;
  aat_.noalias() = a_ * a_.transpose();
  eig_.compute(aat_);
  const auto& ev = eig_.eigenvalues();  // ascending
  const double top = std::max(ev[ev.size() - 1], 0.0);
  const double floor = rel_tol * top;
  for (Eigen::Index i = 0; i < ev.size(); ++i)
    inv_eigenvalues_[i] = (ev[i] > floor && ev[i] > 0.0) ? 1.0 / ev[i] : 0.0;
  sigma_min_ = std::sqrt(std::max(ev[0], 0.0));
  sigma_max_ = std::sqrt(top);
  damped_ = false;
}

void RightInverse::factor_dls(const Eigen::MatrixXd& a, double lambda) {
  assert(a.rows() == a_.rows() && a.cols() == a_.cols());
  a_ = a;
  aat_.noalias() = a_ * a_.transpose();
  aat_.diagonal().array() += lambda * lambda;
  llt_.compute(aat_);
  damped_ = true;
}

void RightInverse::apply(const Eigen::VectorXd& y, Eigen::VectorXd& x) {
  if (damped_) {
    tmp_k_ = y;
    llt_.solveInPlace(tmp_k_);
  } else {
    tmp_k2_.noalias() = eig_.eigenvectors().transpose() * y;
    tmp_k2_.array() *= inv_eigenvalues_.array();
    tmp_k_.noalias() = eig_.eigenvectors() * tmp_k2_;
  }
  x.noalias() = a_.transpose() * tmp_k_;
}

void RightInverse::null_project(const Eigen::VectorXd& z, Eigen::VectorXd& out) {
  tmp_k2_.noalias() = a_ * z;
  const Eigen::VectorXd& az = tmp_k2_;
  // apply() reuses tmp_k2_ in the pinv branch: copy A z first.
  Eigen::VectorXd& y = tmp_k_;
  y = az;
  if (damped_) {
    llt_.solveInPlace(y);
  } else {
    tmp_k2_.noalias() = eig_.eigenvectors().transpose() * y;
    tmp_k2_.array() *= inv_eigenvalues_.array();
    y.noalias() = eig_.eigenvectors() * tmp_k2_;
  }
  out = z;
  out.noalias() -= a_.transpose() * y;
}

}  // namespace rrlab

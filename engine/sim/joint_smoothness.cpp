#include <rrlab/sim/joint_smoothness.hpp>

#include <cmath>
#include <utility>

namespace rrlab {

void JointSmoothnessMeter::restart(const Eigen::VectorXd& q0, double dt) {
  last_q_ = q0;
  const Eigen::Index n = q0.size();
  last_d_.setZero(n);
  last_dd_.setZero(n);
  d_.setZero(n);
  dd_.setZero(n);
  dt_ = dt;
  positions_ = 1;
  n_dd_ = n_ddd_ = 0;
  sum_dd2_ = max_dd_ = sum_ddd2_ = max_ddd_ = 0;
}

void JointSmoothnessMeter::add(const Eigen::VectorXd& q) {
  d_.noalias() = q - last_q_;
  if (positions_ >= 2) {
    dd_.noalias() = d_ - last_d_;
    const double dd = dd_.norm();
    sum_dd2_ += dd * dd;
    if (!(dd <= max_dd_)) max_dd_ = dd;  // a NaN is kept, so the summary shows null
    ++n_dd_;
    if (positions_ >= 3) {
      const double ddd = (dd_ - last_dd_).norm();
      sum_ddd2_ += ddd * ddd;
      if (!(ddd <= max_ddd_)) max_ddd_ = ddd;
      ++n_ddd_;
    }
    std::swap(last_dd_, dd_);  // Eigen swaps the buffers: no copy, no allocation
  }
  std::swap(last_d_, d_);
  last_q_ = q;
  ++positions_;
}

JointSmoothness JointSmoothnessMeter::stats() const {
  JointSmoothness s;
  const double dt2 = dt_ * dt_, dt3 = dt2 * dt_;
  if (n_dd_ > 0) {
    s.rms_qddot = std::sqrt(sum_dd2_ / double(n_dd_)) / dt2;
    s.max_qddot = max_dd_ / dt2;
  }
  if (n_ddd_ > 0) {
    s.rms_jerk = std::sqrt(sum_ddd2_ / double(n_ddd_)) / dt3;
    s.max_jerk = max_ddd_ / dt3;
  }
  return s;
}

}  // namespace rrlab

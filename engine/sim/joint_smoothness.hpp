// How smoothly the arm moved: joint acceleration and jerk by finite
// differences of the joint positions it reached at consecutive steps
// (q_0 the start, q_k the state after step k, dt the scenario's step):
//   q̈_k = (q_{k+1} − 2 q_k + q_{k−1}) / dt²            k = 1 … N−1
//   jerk_k = (q_{k+2} − 3 q_{k+1} + 3 q_k − q_{k−1}) / dt³  k = 1 … N−2
// Each is a vector over the joints; its size at a step is the Euclidean norm
// over all joints in their own units (rad, and m for prismatic joints: 1 m
// weighs as 1 rad, as in the ‖q̇‖ that minimum-norm methods minimise). RMS is
// over the steps of the run, max the largest. The positions reached are
// differenced, not the commanded velocities, so a method that integrates
// itself is measured alike, and the start from rest is no acceleration: a run
// at constant velocity has none. O(1) state: the last position, first and
// second differences; add() does not allocate.
#pragma once

#include <Eigen/Core>

#include <rrlab/sim/frame.hpp>

namespace rrlab {

class JointSmoothnessMeter {
 public:
  // Starts a new history at q0 (sizes the storage: allocates only if the joint count changed).
  void restart(const Eigen::VectorXd& q0, double dt);
  // The next position reached, one dt after the last.
  void add(const Eigen::VectorXd& q);
  // Empty values while there are too few positions: acceleration needs 3, jerk 4.
  JointSmoothness stats() const;

 private:
  Eigen::VectorXd last_q_, last_d_, last_dd_;  // the last position, first and second differences
  Eigen::VectorXd d_, dd_;                     // this step's, swapped into the last ones
  double dt_ = 1;
  long positions_ = 0;
  long n_dd_ = 0, n_ddd_ = 0;
  double sum_dd2_ = 0, max_dd_ = 0, sum_ddd2_ = 0, max_ddd_ = 0;  // of the differences' norms, not yet / dt^k
};

}  // namespace rrlab

// A witness: a joint trajectory that solves a scenario's task (generated
// cases carry one, so a case is known to be solvable). Samples every `dt`
// from t = 0, linear in between, held after the last; the task path of a
// generated case is this trajectory's end-effector trace.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace rrlab {

struct WitnessTrajectory {
  double dt = 0;                     // s between samples
  std::vector<Eigen::VectorXd> q;    // rad; q[0] is the scenario's start

  // The configuration at time t (linear between samples, held outside).
  void at(double t, Eigen::VectorXd& out) const;
  double end_time() const { return q.empty() ? 0.0 : dt * double(q.size() - 1); }
};

}  // namespace rrlab

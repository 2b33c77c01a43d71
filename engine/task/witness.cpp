#include <rrlab/task/witness.hpp>

#include <algorithm>
#include <cmath>

namespace rrlab {

void WitnessTrajectory::at(double t, Eigen::VectorXd& out) const {
  const double last = double(q.size() - 1);
  // 1e-9 of a sample: a step time that is a whole number of samples lands on it
  const double position = std::clamp(t / dt, 0.0, last);
  const double whole = std::min(std::floor(position + 1e-9), last);
  const size_t j = size_t(whole);
  const double u = std::max(0.0, position - whole);
  if (j + 1 >= q.size() || u == 0.0) {
    out = q[j];
    return;
  }
  out = q[j] + u * (q[j + 1] - q[j]);
}

}  // namespace rrlab

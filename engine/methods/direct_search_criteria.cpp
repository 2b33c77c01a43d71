#include <rrlab/methods/direct_search_criteria.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rrlab::kapoor {

Criteria::Criteria(const Model& model, TaskSpace space)
    : n_(model.dof()),
      m_(task_rows(space)),
      centre_(Eigen::VectorXd::Zero(n_)),
      inv_half_range_(Eigen::VectorXd::Zero(n_)),
      jjt_(m_, m_),
      eigenvalues_(m_),
      distance_rows_(std::max(1, model.link_count()), n_),
      distances_now_(std::max(1, model.link_count())),
      delta_theta_(n_),
      point_jacobian_(3, n_) {
  // JRA's θ'_i and 1/θ_i,max (0: the joint does not count)
  const JointLimits& limits = model.limits;
  for (int i = 0; i < n_; ++i) {
    if (!std::isfinite(limits.lower[i]) || !std::isfinite(limits.upper[i])) continue;
    centre_[i] = 0.5 * (limits.lower[i] + limits.upper[i]);
    const double half = 0.5 * (limits.upper[i] - limits.lower[i]);
    if (half > 0) inv_half_range_[i] = 1.0 / half;
  }
}

double Criteria::dexterity(const Eigen::MatrixXd& jacobian, double length) {
  switch (m_) {  // a fixed size unrolls J Jᵀ's loops (the same sums in the same order)
    case 2: gram<2>(jacobian, length); break;
    case 3: gram<3>(jacobian, length); break;
    default: gram<6>(jacobian, length); break;
  }
  eigenvalues_.compute(jjt_);  // the two ends of the spectrum only
  const double lo = eigenvalues_.min(), hi = eigenvalues_.max();
  return lo > 0 ? std::sqrt(hi / lo) : std::numeric_limits<double>::infinity();
}

// jjt_ ← J̃ J̃ᵀ (M = m_ rows; J̃: the position rows of a pose task divided by
// L), a column at a time (contiguous, no scaled copy); L's scaling is
// applied to the sums (1/L² on position × position, 1/L on mixed entries),
// which keeps divisions out of the loop.
template <int M>
void Criteria::gram(const Eigen::MatrixXd& jacobian, double length) {
  double jjt[M][M] = {};
  for (int k = 0; k < n_; ++k) {
    const double* col = jacobian.col(k).data();
    for (int r = 0; r < M; ++r)
      for (int c = 0; c <= r; ++c) jjt[r][c] += col[r] * col[c];
  }
  if (M == 6) {  // pose: the position rows in units of L
    const double inverse = 1.0 / length, inverse2 = inverse * inverse;
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c <= r && c < 3; ++c) jjt[r][c] *= r < 3 ? inverse2 : inverse;
  }
  for (int r = 0; r < M; ++r)
    for (int c = 0; c <= r; ++c) jjt_(r, c) = jjt_(c, r) = jjt[r][c];
}

void Criteria::prepare_clearance(const StepInput& in) {
  has_distances_ = false;
  links_with_distance_ = 0;
  const DistanceTable& table = in.distances;
  for (int link = 0; link < table.links && link < distance_rows_.rows(); ++link) {
    const int o = table.nearest_obstacle(link);
    if (o < 0) continue;
    const LinkObstacleDistance& pair = table.at(link, o);
    point_jacobian_linear(in.model, in.kin, link, pair.on_link, point_jacobian_);
    distance_rows_.row(links_with_distance_).noalias() = pair.normal.transpose() * point_jacobian_;
    distances_now_[links_with_distance_] = pair.distance;
    ++links_with_distance_;
    has_distances_ = true;
  }
}

double Criteria::estimated_clearance(const Eigen::VectorXd& theta, const Eigen::VectorXd& q) {
  double clearance = 0;  // no obstacles: the criterion is constant
  if (!has_distances_) return clearance;
  clearance = std::numeric_limits<double>::infinity();
  delta_theta_.noalias() = theta - q;
  for (int l = 0; l < links_with_distance_; ++l)
    clearance = std::min(clearance, distances_now_[l] + distance_rows_.row(l).dot(delta_theta_));
  return clearance;
}

}  // namespace rrlab::kapoor

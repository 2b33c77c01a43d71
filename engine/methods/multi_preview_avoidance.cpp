#include <rrlab/methods/multi_preview_avoidance.hpp>

#include <algorithm>
#include <cmath>

#include <rrlab/util/rng.hpp>

namespace rrlab {

double unit_ball_volume(int r) {
  // Zhang eq. 19: c_m = 2(2π)^((m−1)/2) / (1·3⋯m) for odd m, (2π)^(m/2) / (2·4⋯m) for even m
  if (r <= 0) return 1.0;
  double c = (r % 2 == 1) ? 2.0 * std::pow(2.0 * M_PI, (r - 1) / 2) : std::pow(2.0 * M_PI, r / 2);
  for (int k = (r % 2 == 1) ? 1 : 2; k <= r; k += 2) c /= k;
  return c;
}

namespace {
int link_point_rows(const Model& model) { return model.kind == ModelKind::planar ? 2 : 3; }
// σ_k below this fraction of σ_1 counts as zero: singular values come from the
// eigenvalues of MMᵀ, whose rounding leaves σ ≈ √ε·σ_1 ≈ 1e-8·σ_1 in a null direction
constexpr double kRankTolerance = 1e-6;
}  // namespace

AvoidanceManipulability::AvoidanceManipulability(const Model& model, TaskSpace space, bool directions)
    : n_(model.dof()),
      rows_(link_point_rows(model)),
      directions_(directions),
      hand_inverse_(task_rows(space), model.dof()),
      null_projector_(model.dof(), model.dof()),
      jacobian3_(3, model.dof()),
      unit_(model.dof()),
      column_(model.dof()) {
  for (int r = 0; r < 4; ++r) ball_volume_[r] = unit_ball_volume(r);
  const int points = std::max(0, model.link_count() - 1);
  point_jacobians_.assign(points, Eigen::MatrixXd::Zero(rows_, n_));
  matrices_.assign(points, Eigen::MatrixXd::Zero(rows_, n_));
  ellipsoids_.resize(points);
  // Generic rank r_i of each point's avoidance matrix: the largest numerical
  // rank over a few configurations (a fixed internal seed: this is a property
  // of the model, not a random choice). V_i is measured in r_i dimensions, so
  // the first and last points of a planar chain give lengths and the others
  // areas (the paper's note under eq. 21), and V_i is continuous in q.
  KinematicsData kin(model);
  Eigen::MatrixXd hand(task_rows(space), n_);
  Rng rng(0x5eed);
  std::vector<int> generic(points, 0);
  for (int sample = 0; sample < 4; ++sample) {
    Eigen::VectorXd q(n_);
    for (int j = 0; j < n_; ++j) q[j] = rng.uniform(-M_PI, M_PI);
    forward_kinematics(model, q, kin);
    task_jacobian(model, kin, space, hand);
    compute(model, kin, hand);
    for (int i = 0; i < points; ++i) generic[i] = std::max(generic[i], ellipsoids_[i].rank);
  }
  for (int i = 0; i < points; ++i) {
    ellipsoids_[i] = AvoidanceEllipsoid{};
    ellipsoids_[i].volume_rank = generic[i];
  }
  amsi_ = 0;
}

double AvoidanceManipulability::compute(const Model& model, const KinematicsData& kin,
                                        const Eigen::MatrixXd& hand_jacobian) {
  hand_inverse_.factor_pinv(hand_jacobian);
  if (!directions_ && point_count() > 0 && ellipsoids_[0].volume_rank > 0) return compute_volumes(model, kin);
  // I − J_n⁺J_n column by column (the null space of the hand task, eq. 2)
  for (int j = 0; j < n_; ++j) {
    unit_.setZero();
    unit_[j] = 1.0;
    hand_inverse_.null_project(unit_, column_);
    null_projector_.col(j) = column_;
  }
  amsi_ = 0;
  for (int i = 0; i < point_count(); ++i) {
    const Eigen::Vector3d point = kin.link_end.col(i);
    point_jacobian_linear(model, kin, i, point, jacobian3_);
    point_jacobians_[i] = jacobian3_.topRows(rows_);
    // Zhang eq. 5: ¹M_i = J_i (I − J_n⁺J_n)
    matrices_[i].noalias() = point_jacobians_[i] * null_projector_;
    ellipsoids_[i].centre = point;
    decompose(i);
    // Zhang eq. 21: ¹E = Σ ¹V_i a_i with a_i = 1 m^(−r_i): a number without unit
    amsi_ += ellipsoids_[i].volume;
  }
  return amsi_;
}

double AvoidanceManipulability::compute_volumes(const Model& model, const KinematicsData& kin) {
  // ¹M_i row by row: its rows are the rows of J_i projected onto the hand's
  // null space, (I − J_n⁺J_n) J_iᵀ (the projector is symmetric) — m projections
  // per point instead of the n x n projector and its product
  amsi_ = 0;
  for (int i = 0; i < point_count(); ++i) {
    const Eigen::Vector3d point = kin.link_end.col(i);
    point_jacobian_linear(model, kin, i, point, jacobian3_);
    point_jacobians_[i] = jacobian3_.topRows(rows_);
    for (int r = 0; r < rows_; ++r) {
      unit_ = point_jacobians_[i].row(r).transpose();
      hand_inverse_.null_project(unit_, column_);
      matrices_[i].row(r) = column_.transpose();
    }
    AvoidanceEllipsoid& e = ellipsoids_[i];
    e.centre = point;
    // Zhang eq. 18, 20: ¹V_i = c · σ_1 ⋯ σ_r with r the generic rank, whose
    // other σ are 0: σ_1² ⋯ σ_r² is then e_r, the r-th elementary symmetric
    // function of the eigenvalues of ¹M_i ¹M_iᵀ — the sum of its principal
    // r x r minors (trace, 2 x 2 minors, determinant); no eigen-decomposition
    Eigen::Matrix3d mmt = Eigen::Matrix3d::Zero();
    mmt.topLeftCorner(rows_, rows_).noalias() = matrices_[i] * matrices_[i].transpose();
    double product = 0;
    switch (e.volume_rank) {
      case 1: product = mmt.trace(); break;
      case 2:
        product = mmt(0, 0) * mmt(1, 1) - mmt(0, 1) * mmt(1, 0) + mmt(0, 0) * mmt(2, 2) - mmt(0, 2) * mmt(2, 0) +
                  mmt(1, 1) * mmt(2, 2) - mmt(1, 2) * mmt(2, 1);
        break;
      case 3: product = mmt.determinant(); break;
    }
    e.volume = ball_volume_[e.volume_rank] * std::sqrt(std::max(product, 0.0));
    amsi_ += e.volume;
  }
  return amsi_;
}

void AvoidanceManipulability::decompose(int i) {
  // singular values / left singular vectors of ¹M_i from ¹M_i ¹M_iᵀ (m x m,
  // padded to 3 x 3 for planar models: the padding adds a zero)
  Eigen::Matrix3d mmt = Eigen::Matrix3d::Zero();
  mmt.topLeftCorner(rows_, rows_).noalias() = matrices_[i] * matrices_[i].transpose();
  // eigenvalues only where no direction is wanted: the QR iterations on the
  // tridiagonal form are the same either way, so are the eigenvalues
  eig_.compute(mmt, directions_ ? Eigen::ComputeEigenvectors : Eigen::EigenvaluesOnly);
  AvoidanceEllipsoid& e = ellipsoids_[i];
  const double scale = std::sqrt(std::max(eig_.eigenvalues()[2], 0.0));
  e.rank = 0;
  for (int k = 0; k < 3; ++k) {
    const int from = 2 - k;  // eigenvalues ascend
    e.sigma[k] = std::sqrt(std::max(eig_.eigenvalues()[from], 0.0));
    if (directions_) e.directions.col(k) = eig_.eigenvectors().col(from);
    if (k < rows_ && e.sigma[k] > kRankTolerance * scale && e.sigma[k] > 1e-300) ++e.rank;
  }
  // Zhang eq. 18, 20: ¹V_i = c · σ_1 ⋯ σ_r over the generic rank r_i (before
  // the ranks are known, over the numerical rank)
  const int r = e.volume_rank > 0 ? e.volume_rank : e.rank;
  double w = 1.0;
  for (int k = 0; k < r; ++k) w *= e.sigma[k];
  e.volume = r > 0 ? unit_ball_volume(r) * w : 0.0;
}

std::vector<Eigen::MatrixXd> plural_avoidance_matrices(const std::vector<Eigen::MatrixXd>& point_jacobians,
                                                       const Eigen::MatrixXd& hand_jacobian,
                                                       const std::vector<int>& realised) {
  const Eigen::Index n = hand_jacobian.cols();
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(n, n);
  auto pinv = [](const Eigen::MatrixXd& a) {
    return a.completeOrthogonalDecomposition().pseudoInverse();
  };
  // chain of projectors: (I − J_n⁺J_n)(I − ¹M_i⁺¹M_i)(I − ²M_j⁺²M_j)⋯
  Eigen::MatrixXd chain = identity - pinv(hand_jacobian) * hand_jacobian;
  for (int point : realised) {
    const Eigen::MatrixXd m = point_jacobians.at(point) * chain;  // this task's own avoidance matrix
    chain = chain * (identity - pinv(m) * m);
  }
  std::vector<Eigen::MatrixXd> out;
  out.reserve(point_jacobians.size());
  for (const Eigen::MatrixXd& j : point_jacobians) out.push_back(j * chain);
  return out;
}

double obstacle_potential(const DistanceTable& distances, double width, double height) {
  double sum = 0;
  for (const LinkObstacleDistance& pair : distances.pairs) {
    const double band = 1.0 - pair.distance / width;
    if (band > 0) sum += band * band;
  }
  return -height * sum;
}

}  // namespace rrlab

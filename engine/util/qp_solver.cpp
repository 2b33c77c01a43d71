// Goldfarb–Idnani dual active set. Notation of the paper (and of quadprog):
// H = LLᵀ, J = L⁻ᵀQ with QR = L⁻¹N for the active normals N; J = [J₁ J₂]
// splits at q (active count), z = J₂J₂ᵀn is the primal step direction and
// r = R⁻¹J₁ᵀn the change of the active multipliers per unit of the new one.
#include <rrlab/util/qp_solver.hpp>

#include <algorithm>
#include <cmath>

namespace rrlab {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// z counts as zero (the new normal lies in the span of the active ones) when
// |J₂ᵀn|² ≤ kDependent · |Jᵀn|².
constexpr double kDependent = 1e-14;

// Givens rotation that maps (a, b) to (h, 0); returns false when both are 0.
bool givens(double a, double b, double& c, double& s, double& h) {
  h = std::hypot(a, b);
  if (h == 0.0) return false;
  c = a / h;
  s = b / h;
  return true;
}

}  // namespace

const char* to_string(QpStatus status) {
  switch (status) {
    case QpStatus::optimal: return "optimal";
    case QpStatus::infeasible: return "infeasible";
    case QpStatus::max_iterations: return "max_iterations";
    case QpStatus::invalid_input: return "invalid_input";
    case QpStatus::numerical_failure: return "numerical_failure";
  }
  return "?";
}

QpProblem::QpProblem(int n, int eq_capacity, int ineq_capacity)
    : H(Eigen::MatrixXd::Identity(n, n)),
      g(Eigen::VectorXd::Zero(n)),
      A_eq(Eigen::MatrixXd::Zero(eq_capacity, n)),
      b_eq(Eigen::VectorXd::Zero(eq_capacity)),
      A_in(Eigen::MatrixXd::Zero(ineq_capacity, n)),
      b_in(Eigen::VectorXd::Constant(ineq_capacity, -kInf)),
      lower(Eigen::VectorXd::Constant(n, -kInf)),
      upper(Eigen::VectorXd::Constant(n, kInf)) {}

QpSolver::QpSolver(int n, int eq_capacity, int ineq_capacity)
    : n_(n),
      me_cap_(eq_capacity),
      mi_cap_(ineq_capacity),
      H_cached_(Eigen::MatrixXd::Zero(n, n)),
      llt_(n),
      J0_(n, n),
      J_(n, n),
      R_(Eigen::MatrixXd::Zero(n, n)),
      x_(Eigen::VectorXd::Zero(n)),
      d_(n),
      z_(n),
      r_(n),
      u_(Eigen::VectorXd::Zero(n)),
      slack_in_(ineq_capacity),
      active_(Eigen::VectorXi::Constant(n, -1)),
      warm_(Eigen::VectorXi::Constant(n, -1)),
      is_active_(Eigen::Matrix<bool, Eigen::Dynamic, 1>::Constant(eq_capacity + ineq_capacity + 2 * n, false)),
      excluded_(Eigen::Matrix<bool, Eigen::Dynamic, 1>::Constant(eq_capacity + ineq_capacity + 2 * n, false)),
      lambda_eq_(Eigen::VectorXd::Zero(eq_capacity)),
      mu_in_(Eigen::VectorXd::Zero(ineq_capacity)),
      mu_lower_(Eigen::VectorXd::Zero(n)),
      mu_upper_(Eigen::VectorXd::Zero(n)),
      hx_(n) {}

// ---- constraint access (ids are stable across solves: capacities, not counts)

double QpSolver::slack(const QpProblem& p, int id) const {
  if (id < me_cap_) return p.A_eq.row(id).dot(x_) - p.b_eq[id];
  id -= me_cap_;
  if (id < mi_cap_) return p.A_in.row(id).dot(x_) - p.b_in[id];
  id -= mi_cap_;
  if (id < n_) return x_[id] - p.lower[id];
  id -= n_;
  return p.upper[id] - x_[id];
}

double QpSolver::rhs_scale(const QpProblem& p, int id) const {
  if (id < me_cap_) return 1.0 + std::abs(p.b_eq[id]);
  id -= me_cap_;
  if (id < mi_cap_) return 1.0 + std::abs(p.b_in[id]);
  id -= mi_cap_;
  if (id < n_) return 1.0 + std::abs(p.lower[id]);
  return 1.0 + std::abs(p.upper[id - n_]);
}

void QpSolver::direction(const QpProblem& p, int id) {
  if (id < me_cap_) {
    d_.noalias() = J_.transpose() * p.A_eq.row(id).transpose();
  } else if (id < me_cap_ + mi_cap_) {
    d_.noalias() = J_.transpose() * p.A_in.row(id - me_cap_).transpose();
  } else if (id < me_cap_ + mi_cap_ + n_) {
    d_ = J_.row(id - me_cap_ - mi_cap_).transpose();
  } else {
    d_ = -J_.row(id - me_cap_ - mi_cap_ - n_).transpose();
  }
  const int free = n_ - q_;
  z_.noalias() = J_.rightCols(free) * d_.tail(free);
  r_.head(q_) = d_.head(q_);
  R_.topLeftCorner(q_, q_).triangularView<Eigen::Upper>().solveInPlace(r_.head(q_));
}

double QpSolver::z_dot_normal(const QpProblem& p, int id) const {
  if (id < me_cap_) return p.A_eq.row(id).dot(z_);
  id -= me_cap_;
  if (id < mi_cap_) return p.A_in.row(id).dot(z_);
  id -= mi_cap_;
  if (id < n_) return z_[id];
  return -z_[id - n_];
}

// Appends constraint `id` (whose d = Jᵀn was just computed) to the active set:
// rotate d[q+1..n) to zero, updating J, and make d[0..q] the new column of R.
bool QpSolver::add_active(int id) {
  double c, s, h;
  for (int j = n_ - 1; j > q_; --j) {
    if (!givens(d_[j - 1], d_[j], c, s, h)) continue;
    d_[j - 1] = h;
    d_[j] = 0.0;
    for (int k = 0; k < n_; ++k) {
      const double a = J_(k, j - 1), b = J_(k, j);
      J_(k, j - 1) = c * a + s * b;
      J_(k, j) = -s * a + c * b;
    }
  }
  if (std::abs(d_[q_]) <= 1e-14 * r_norm_) return false;
  r_norm_ = std::max(r_norm_, std::abs(d_[q_]));
  R_.col(q_).head(q_ + 1) = d_.head(q_ + 1);
  R_.col(q_).tail(n_ - q_ - 1).setZero();
  active_[q_] = id;
  is_active_[id] = true;
  ++q_;
  return true;
}

// Removes the constraint at active position `pos`; restores R to upper
// triangular form with Givens rotations applied to rows of R and columns of J.
void QpSolver::drop_active(int pos) {
  is_active_[active_[pos]] = false;
  for (int j = pos; j < q_ - 1; ++j) {
    active_[j] = active_[j + 1];
    u_[j] = u_[j + 1];
    R_.col(j) = R_.col(j + 1);
  }
  --q_;
  active_[q_] = -1;
  u_[q_] = 0;
  R_.col(q_).setZero();
  double c, s, h;
  for (int j = pos; j < q_; ++j) {
    if (!givens(R_(j, j), R_(j + 1, j), c, s, h)) continue;
    R_(j, j) = h;
    R_(j + 1, j) = 0.0;
    for (int k = j + 1; k < q_; ++k) {
      const double a = R_(j, k), b = R_(j + 1, k);
      R_(j, k) = c * a + s * b;
      R_(j + 1, k) = -s * a + c * b;
    }
    for (int k = 0; k < n_; ++k) {
      const double a = J_(k, j), b = J_(k, j + 1);
      J_(k, j) = c * a + s * b;
      J_(k, j + 1) = -s * a + c * b;
    }
  }
}

bool QpSolver::factor(const QpProblem& p) {
  if (factored_ && p.H == H_cached_) return true;
  factored_ = false;
  H_cached_ = p.H;
  llt_.compute(p.H);
  if (llt_.info() != Eigen::Success) return false;
  const auto& lower_factor = llt_.matrixLLT();
  for (int i = 0; i < n_; ++i)
    if (!(lower_factor(i, i) > 1e-14 * lower_factor.diagonal().cwiseAbs().maxCoeff())) return false;
  J0_.setIdentity();
  llt_.matrixU().solveInPlace(J0_);  // J0 = L⁻ᵀ
  factored_ = true;
  return true;
}

// The most violated inequality not excluded; false when none is violated.
bool QpSolver::violated_most(const QpProblem& p, int& id, double& s) {
  double worst = 0;
  id = -1;
  if (mi_ > 0) {
    slack_in_.head(mi_).noalias() = p.A_in.topRows(mi_) * x_;
    slack_in_.head(mi_) -= p.b_in.head(mi_);
    for (int k = 0; k < mi_; ++k) {
      const int cid = me_cap_ + k;
      const double scaled = slack_in_[k] / (1.0 + std::abs(p.b_in[k]));
      if (scaled < -tol_ && scaled < worst && !is_active_[cid] && !excluded_[cid]) worst = scaled, id = cid;
    }
  }
  for (int i = 0; i < n_; ++i) {
    const int lo = me_cap_ + mi_cap_ + i, up = lo + n_;
    const double slo = (x_[i] - p.lower[i]) / (1.0 + std::abs(p.lower[i]));
    const double sup = (p.upper[i] - x_[i]) / (1.0 + std::abs(p.upper[i]));
    if (slo < -tol_ && slo < worst && !is_active_[lo] && !excluded_[lo]) worst = slo, id = lo;
    if (sup < -tol_ && sup < worst && !is_active_[up] && !excluded_[up]) worst = sup, id = up;
  }
  if (id < 0) return false;
  s = slack(p, id);
  return true;
}

void QpSolver::finish(const QpProblem& p) {
  lambda_eq_.setZero();
  mu_in_.setZero();
  mu_lower_.setZero();
  mu_upper_.setZero();
  warm_count_ = 0;
  for (int j = 0; j < q_; ++j) {
    int id = active_[j];
    const double u = u_[j];
    if (id < me_cap_) {
      lambda_eq_[id] = u;
      continue;
    }
    warm_[warm_count_++] = id;
    id -= me_cap_;
    if (id < mi_cap_) {
      mu_in_[id] = u;
      continue;
    }
    id -= mi_cap_;
    if (id < n_)
      mu_lower_[id] = u;
    else
      mu_upper_[id - n_] = u;
  }
  hx_.noalias() = p.H * x_;
  objective_ = 0.5 * x_.dot(hx_) + p.g.dot(x_);
}

double QpSolver::objective() const { return objective_; }

bool QpSolver::inequality_active(int row) const { return is_active_[me_cap_ + row]; }
bool QpSolver::lower_active(int i) const { return is_active_[me_cap_ + mi_cap_ + i]; }
bool QpSolver::upper_active(int i) const { return is_active_[me_cap_ + mi_cap_ + n_ + i]; }

// Stays whole (over 100 lines): Goldfarb & Idnani's dual active-set loop
// (choose a violated constraint, step in primal and dual space, drop a
// blocking constraint or add the chosen one) in the paper's order; its steps
// share the working set and the J, R factors, which a split would pass around.
QpStatus QpSolver::solve(const QpProblem& p) {
  me_ = p.eq_count;
  mi_ = p.ineq_count;
  iterations_ = 0;
  const bool sizes_ok = p.n() == n_ && me_ >= 0 && me_ <= me_cap_ && mi_ >= 0 && mi_ <= mi_cap_ &&
                        p.A_eq.rows() >= me_ && p.A_in.rows() >= mi_;
  auto invalid = [&] {
    x_.setZero();
    q_ = 0;
    is_active_.setConstant(false);
    warm_count_ = 0;
    lambda_eq_.setZero(), mu_in_.setZero(), mu_lower_.setZero(), mu_upper_.setZero();
    return QpStatus::invalid_input;
  };
  if (!sizes_ok) return invalid();
  // data checks: finite matrices, no +inf lower / −inf upper, lower ≤ upper
  if (!p.H.allFinite() || !p.g.allFinite() || !p.A_eq.topRows(me_).allFinite() ||
      !p.b_eq.head(me_).allFinite() || !p.A_in.topRows(mi_).allFinite())
    return invalid();
  for (int k = 0; k < mi_; ++k)
    if (std::isnan(p.b_in[k]) || p.b_in[k] == kInf) return invalid();
  for (int i = 0; i < n_; ++i)
    if (std::isnan(p.lower[i]) || std::isnan(p.upper[i]) || p.lower[i] == kInf || p.upper[i] == -kInf)
      return invalid();
  if (!factor(p)) return invalid();

  const int max_iterations = max_iterations_ > 0 ? max_iterations_ : 10 * (me_ + mi_ + 2 * n_) + 20;
  J_ = J0_;
  R_.setZero();
  u_.setZero();
  q_ = 0;
  r_norm_ = 1.0;
  is_active_.setConstant(false);
  excluded_.setConstant(false);
  // unconstrained minimum x = −H⁻¹g = −J0 J0ᵀ g
  d_.noalias() = J0_.transpose() * p.g;
  x_.noalias() = -J0_ * d_;

  // equalities: full steps, multipliers of free sign
  for (int k = 0; k < me_; ++k) {
    direction(p, k);
    const double s = slack(p, k);
    const double zn = z_dot_normal(p, k);
    if (zn <= kDependent * d_.squaredNorm()) {
      // linearly dependent on earlier equalities: redundant if consistent
      if (std::abs(s) <= 1e-9 * rhs_scale(p, k)) continue;
      finish(p);
      return QpStatus::infeasible;
    }
    const double t = -s / zn;
    x_ += t * z_;
    u_.head(q_) -= t * r_.head(q_);
    if (!add_active(k)) {
      finish(p);
      return QpStatus::numerical_failure;
    }
    u_[q_ - 1] = t;
  }
  eq_active_ = q_;

  int warm_pos = 0;
  const int warm_total = warm_start_ ? warm_count_ : 0;
  while (true) {
    // choose a violated inequality: the previous optimum's active set first
    int p_id = -1;
    double s_p = 0;
    while (warm_pos < warm_total) {
      const int id = warm_[warm_pos++];
      if (id >= me_cap_ + mi_ && id < me_cap_ + mi_cap_) continue;  // row beyond the current count
      const double s = slack(p, id);
      if (!is_active_[id] && s < -tol_ * rhs_scale(p, id)) {
        p_id = id, s_p = s;
        break;
      }
    }
    if (p_id < 0 && !violated_most(p, p_id, s_p)) {
      // optimal unless an excluded constraint is still violated
      for (int id = me_cap_; id < me_cap_ + mi_cap_ + 2 * n_; ++id) {
        if (!excluded_[id]) continue;
        if (slack(p, id) < -tol_ * rhs_scale(p, id)) {
          finish(p);
          return QpStatus::numerical_failure;
        }
      }
      finish(p);
      return QpStatus::optimal;
    }
    double u_p = 0;
    while (true) {
      if (++iterations_ > max_iterations) {
        finish(p);
        return QpStatus::max_iterations;
      }
      direction(p, p_id);
      // partial step: the first active inequality whose multiplier reaches 0
      double t1 = kInf;
      int leave = -1;
      for (int j = eq_active_; j < q_; ++j) {
        if (r_[j] > 0) {
          const double ratio = u_[j] / r_[j];
          if (ratio < t1) t1 = ratio, leave = j;
        }
      }
      const double zn = z_dot_normal(p, p_id);
      const double t2 = zn > kDependent * d_.squaredNorm() ? -s_p / zn : kInf;
      const double t = std::min(t1, t2);
      if (t == kInf) {
        finish(p);
        return QpStatus::infeasible;
      }
      if (t2 == kInf) {  // dual step only
        u_.head(q_) -= t * r_.head(q_);
        u_p += t;
        drop_active(leave);
        continue;
      }
      x_ += t * z_;
      u_.head(q_) -= t * r_.head(q_);
      u_p += t;
      if (t2 <= t1) {  // full step: p becomes active
        if (!add_active(p_id)) {
          excluded_[p_id] = true;
        } else {
          u_[q_ - 1] = u_p;
        }
        break;
      }
      drop_active(leave);  // partial step
      s_p = slack(p, p_id);
    }
  }
}

}  // namespace rrlab

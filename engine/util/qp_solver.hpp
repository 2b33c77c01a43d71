// Dense strictly convex QP on Eigen: the dual active-set method of Goldfarb &
// Idnani (Math. Programming 27, 1983), numerically stable form with Givens
// updates of J = L⁻ᵀQ and R (as in quadprog / eiquadprog).
//
//   minimise   ½ xᵀHx + gᵀx
//   subject to A_eq x  = b_eq            (the first eq_count rows)
//              A_in x ≥ b_in             (the first ineq_count rows)
//              lower ≤ x ≤ upper         (±inf: no bound)
//
// H must be symmetric positive definite. Everything is sized at construction
// (capacities); solve() does not allocate. The Cholesky factor of H is kept
// while H does not change. Warm start: the inequalities that were active at
// the last optimum are tried first (Goldfarb–Idnani may add any violated
// constraint next, so this changes the path, never the answer).
// Multipliers follow Hx + g = A_eqᵀλ + A_inᵀμ + μ_lower − μ_upper, μ ≥ 0.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <limits>

namespace rrlab {

enum class QpStatus {
  optimal,
  infeasible,          // no point satisfies the constraints (or equalities contradict)
  max_iterations,      // the iteration bound was hit: x is the last dual iterate
  invalid_input,       // H not positive definite, non-finite data, lower > upper
  numerical_failure,   // a constraint could not be added (degenerate beyond tolerance)
};
const char* to_string(QpStatus status);

struct QpProblem {
  QpProblem(int n, int eq_capacity, int ineq_capacity);
  int n() const { return static_cast<int>(g.size()); }

  Eigen::MatrixXd H;
  Eigen::VectorXd g;
  Eigen::MatrixXd A_eq;
  Eigen::VectorXd b_eq;
  int eq_count = 0;
  Eigen::MatrixXd A_in;
  Eigen::VectorXd b_in;
  int ineq_count = 0;
  Eigen::VectorXd lower, upper;  // box; default ±inf
};

class QpSolver {
 public:
  QpSolver(int n, int eq_capacity, int ineq_capacity);

  QpStatus solve(const QpProblem& problem);

  const Eigen::VectorXd& x() const { return x_; }
  double objective() const;  // ½xᵀHx + gᵀx of the last solve
  // Multipliers of the last solve (zero for inactive constraints).
  const Eigen::VectorXd& eq_multipliers() const { return lambda_eq_; }
  const Eigen::VectorXd& ineq_multipliers() const { return mu_in_; }
  const Eigen::VectorXd& lower_multipliers() const { return mu_lower_; }
  const Eigen::VectorXd& upper_multipliers() const { return mu_upper_; }
  int iterations() const { return iterations_; }
  // Inequalities (general rows and bounds) active at the last optimum.
  int active_inequalities() const { return warm_count_; }
  bool inequality_active(int row) const;  // general row of A_in
  bool lower_active(int i) const;
  bool upper_active(int i) const;

  void set_max_iterations(int max_iterations) { max_iterations_ = max_iterations; }
  void set_warm_start(bool on) { warm_start_ = on; }
  void forget_warm_start() { warm_count_ = 0; }
  // Primal feasibility tolerance (absolute, scaled by 1 + |rhs|).
  void set_tolerance(double tol) { tol_ = tol; }

 private:
  // Constraint ids: [0, me) equalities, [me, me + mi) general inequalities,
  // then n lower bounds, then n upper bounds.
  double slack(const QpProblem& p, int id) const;  // nᵀx − rhs
  double rhs_scale(const QpProblem& p, int id) const;
  void direction(const QpProblem& p, int id);    // d = Jᵀn, z = J₂d₂, r = R⁻¹d₁
  double z_dot_normal(const QpProblem& p, int id) const;
  bool add_active(int id);
  void drop_active(int position);
  bool factor(const QpProblem& p);
  void finish(const QpProblem& p);
  bool violated_most(const QpProblem& p, int& id, double& s);

  int n_, me_cap_, mi_cap_;
  int me_ = 0, mi_ = 0;
  Eigen::MatrixXd H_cached_;
  bool factored_ = false;
  Eigen::LLT<Eigen::MatrixXd> llt_;
  Eigen::MatrixXd J0_, J_, R_;
  Eigen::VectorXd x_, d_, z_, r_, u_, slack_in_;
  Eigen::VectorXi active_;  // constraint ids in the active set, positions [0, q)
  Eigen::VectorXi warm_;    // inequality ids active at the last optimum
  Eigen::Matrix<bool, Eigen::Dynamic, 1> is_active_, excluded_;
  int q_ = 0, eq_active_ = 0, warm_count_ = 0;
  double r_norm_ = 1;
  Eigen::VectorXd lambda_eq_, mu_in_, mu_lower_, mu_upper_;
  Eigen::VectorXd hx_;
  double objective_ = 0;
  int iterations_ = 0, max_iterations_ = 0;
  bool warm_start_ = true;
  double tol_ = 1e-10;
};

}  // namespace rrlab

// Goldfarb–Idnani QP: random strictly convex problems against the KKT
// conditions, closed-form solutions, degenerate and infeasible problems.
#include <rrlab/util/qp_solver.hpp>

#include <gtest/gtest.h>

#include <random>

namespace rrlab {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct KktReport {
  double stationarity = 0, equality = 0, inequality = 0, dual = 0, complementarity = 0;
};

// Largest violation of each KKT condition at the solver's solution.
KktReport kkt(const QpProblem& p, const QpSolver& s) {
  const Eigen::VectorXd& x = s.x();
  Eigen::VectorXd grad = p.H * x + p.g;
  grad -= p.A_eq.topRows(p.eq_count).transpose() * s.eq_multipliers().head(p.eq_count);
  grad -= p.A_in.topRows(p.ineq_count).transpose() * s.ineq_multipliers().head(p.ineq_count);
  grad -= s.lower_multipliers();
  grad += s.upper_multipliers();
  KktReport r;
  r.stationarity = grad.cwiseAbs().maxCoeff();
  if (p.eq_count > 0)
    r.equality = (p.A_eq.topRows(p.eq_count) * x - p.b_eq.head(p.eq_count)).cwiseAbs().maxCoeff();
  auto inequality = [&](double slack, double mu) {
    r.inequality = std::max(r.inequality, -slack);
    r.dual = std::max(r.dual, -mu);
    if (std::isfinite(slack)) r.complementarity = std::max(r.complementarity, std::abs(mu * slack));
  };
  for (int k = 0; k < p.ineq_count; ++k)
    inequality(p.A_in.row(k).dot(x) - p.b_in[k], s.ineq_multipliers()[k]);
  for (int i = 0; i < p.n(); ++i) {
    inequality(x[i] - p.lower[i], s.lower_multipliers()[i]);
    inequality(p.upper[i] - x[i], s.upper_multipliers()[i]);
  }
  return r;
}

void expect_kkt(const QpProblem& p, const QpSolver& s, double tol, const std::string& label) {
  const KktReport r = kkt(p, s);
  EXPECT_LE(r.stationarity, tol) << label;
  EXPECT_LE(r.equality, tol) << label;
  EXPECT_LE(r.inequality, tol) << label;
  EXPECT_LE(r.dual, tol) << label;
  EXPECT_LE(r.complementarity, tol) << label;
}

// A feasible random problem: constraints built around a random point x0.
void random_problem(std::mt19937& rng, QpProblem& p, int me, int mi, bool box, Eigen::VectorXd* point = nullptr) {
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int n = p.n();
  Eigen::MatrixXd m(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) m(i, j) = normal(rng);
  p.H = m * m.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
  Eigen::VectorXd x0(n);
  for (int i = 0; i < n; ++i) p.g[i] = 3 * normal(rng), x0[i] = normal(rng);
  p.eq_count = me;
  p.ineq_count = mi;
  for (int k = 0; k < me; ++k) {
    for (int i = 0; i < n; ++i) p.A_eq(k, i) = normal(rng);
    p.b_eq[k] = p.A_eq.row(k).dot(x0);
  }
  for (int k = 0; k < mi; ++k) {
    for (int i = 0; i < n; ++i) p.A_in(k, i) = normal(rng);
    // some constraints pass through x0 (tight), others leave room
    p.b_in[k] = p.A_in.row(k).dot(x0) - (unit(rng) < 0.3 ? 0.0 : unit(rng));
  }
  for (int i = 0; i < n; ++i) {
    p.lower[i] = box ? x0[i] - 0.5 * unit(rng) : -kInf;
    p.upper[i] = box ? x0[i] + 0.5 * unit(rng) : kInf;
  }
  if (point) *point = x0;
}

TEST(QpSolver, RandomStrictlyConvexProblemsMeetKkt) {
  std::mt19937 rng(12345);
  int solved = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int n = 2 + trial % 9;
    const int me = trial % 3 == 0 ? 0 : static_cast<int>(rng() % n);
    const int mi = static_cast<int>(rng() % (4 * n));
    QpProblem p(n, n, 4 * n);
    random_problem(rng, p, me, mi, trial % 2 == 0);
    QpSolver solver(n, n, 4 * n);
    const QpStatus status = solver.solve(p);
    ASSERT_EQ(status, QpStatus::optimal) << "trial " << trial;
    expect_kkt(p, solver, 1e-9, "trial " + std::to_string(trial));
    ++solved;
  }
  EXPECT_EQ(solved, 400);
}

TEST(QpSolver, RandomDegenerateProblemsMeetKkt) {
  // duplicated and scaled copies of rows, equalities repeated as two
  // inequalities, box bounds equal to each other: still optimal, still KKT
  std::mt19937 rng(99);
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 2 + trial % 7, me = static_cast<int>(rng() % n), mi = static_cast<int>(rng() % (3 * n));
    QpProblem p(n, n, 6 * n + 2);
    Eigen::VectorXd x0;
    random_problem(rng, p, me, mi, trial % 2 == 0, &x0);
    int rows = mi;
    for (int k = 0; k < mi && rows < 6 * n; k += 2) {  // duplicates, some scaled
      const double scale = 1.0 + (k % 3);
      p.A_in.row(rows) = scale * p.A_in.row(k);
      p.b_in[rows++] = scale * p.b_in[k];
    }
    if (me > 0 && rows + 2 <= 6 * n + 2) {  // an equality written as two inequalities
      p.A_in.row(rows) = p.A_eq.row(0);
      p.b_in[rows++] = p.b_eq[0];
      p.A_in.row(rows) = -p.A_eq.row(0);
      p.b_in[rows++] = -p.b_eq[0];
    }
    p.ineq_count = rows;
    if (trial % 2 == 0) p.lower[0] = p.upper[0] = x0[0];  // a fixed variable (x0 stays feasible)
    QpSolver solver(n, n, 6 * n + 2);
    const QpStatus status = solver.solve(p);
    ASSERT_EQ(status, QpStatus::optimal) << "trial " << trial;
    expect_kkt(p, solver, 1e-9, "degenerate trial " + std::to_string(trial));
  }
}

TEST(QpSolver, WarmStartGivesTheSameSolutionInFewerIterations) {
  std::mt19937 rng(7);
  long cold_iterations = 0, warm_iterations = 0;
  for (int trial = 0; trial < 50; ++trial) {
    QpProblem p(7, 6, 30);
    random_problem(rng, p, 6, 30, true);
    QpSolver solver(7, 6, 30);
    ASSERT_EQ(solver.solve(p), QpStatus::optimal);
    const Eigen::VectorXd cold = solver.x();
    cold_iterations += solver.iterations();
    // the next step's problem differs a little: same active set expected
    p.g *= 1.001;
    ASSERT_EQ(solver.solve(p), QpStatus::optimal);
    warm_iterations += solver.iterations();
    expect_kkt(p, solver, 1e-9, "warm " + std::to_string(trial));
    QpSolver fresh(7, 6, 30);
    ASSERT_EQ(fresh.solve(p), QpStatus::optimal);
    EXPECT_LT((fresh.x() - solver.x()).norm(), 1e-9);
    EXPECT_LT((cold - solver.x()).norm(), 0.1);
  }
  EXPECT_LE(warm_iterations, cold_iterations);
}

TEST(QpSolver, BoxOnlyProblemIsAClamp) {
  // min ½|x − c|² s.t. l ≤ x ≤ u: x = clamp(c, l, u), μ = the clamped excess
  QpProblem p(4, 0, 0);
  const Eigen::Vector4d c(2.0, -3.0, 0.5, -0.2);
  p.g = -c;
  p.lower << -1, -1, -1, 0;
  p.upper << 1, 1, 1, kInf;
  QpSolver solver(4, 0, 0);
  ASSERT_EQ(solver.solve(p), QpStatus::optimal);
  EXPECT_NEAR(solver.x()[0], 1.0, 1e-14);
  EXPECT_NEAR(solver.x()[1], -1.0, 1e-14);
  EXPECT_NEAR(solver.x()[2], 0.5, 1e-14);
  EXPECT_NEAR(solver.x()[3], 0.0, 1e-14);
  EXPECT_NEAR(solver.upper_multipliers()[0], 1.0, 1e-12);
  EXPECT_NEAR(solver.lower_multipliers()[1], 2.0, 1e-12);
  EXPECT_NEAR(solver.lower_multipliers()[3], 0.2, 1e-12);
  EXPECT_TRUE(solver.upper_active(0));
  EXPECT_FALSE(solver.lower_active(2));
}

TEST(QpSolver, MinimumNormSolutionOfAnEqualityIsThePseudoinverse) {
  // min ½|x|² s.t. Ax = b: x = Aᵀ(AAᵀ)⁻¹b
  QpProblem p(5, 2, 0);
  p.eq_count = 2;
  p.A_eq << 1, 2, 0, -1, 0.5, 0, 1, 1, 1, -2;
  p.b_eq << 0.3, -1.2;
  QpSolver solver(5, 2, 0);
  ASSERT_EQ(solver.solve(p), QpStatus::optimal);
  const Eigen::MatrixXd a = p.A_eq;
  const Eigen::VectorXd expected = a.transpose() * (a * a.transpose()).ldlt().solve(p.b_eq);
  EXPECT_LT((solver.x() - expected).norm(), 1e-13);
}

TEST(QpSolver, HalfSpaceProjectionInClosedForm) {
  // min ½|x − c|² s.t. aᵀx ≥ b with aᵀc < b: x = c + (b − aᵀc) a/|a|², μ = (b − aᵀc)/|a|²
  QpProblem p(3, 0, 1);
  const Eigen::Vector3d c(0.2, -0.4, 1.0), a(1.0, 2.0, -2.0);
  p.g = -c;
  p.ineq_count = 1;
  p.A_in.row(0) = a.transpose();
  p.b_in[0] = 1.0;
  QpSolver solver(3, 0, 1);
  ASSERT_EQ(solver.solve(p), QpStatus::optimal);
  const double excess = 1.0 - a.dot(c);
  EXPECT_LT((solver.x() - (c + excess * a / a.squaredNorm())).norm(), 1e-14);
  EXPECT_NEAR(solver.ineq_multipliers()[0], excess / a.squaredNorm(), 1e-14);
}

TEST(QpSolver, DegenerateConstraintsStillSolve) {
  // duplicated inequality rows, a redundant equality and a vertex where more
  // constraints are active than there are variables
  QpProblem p(2, 3, 5);
  p.g << -3, -3;  // unconstrained minimum (3, 3)
  p.eq_count = 2;
  p.A_eq << 1, -1, 2, -2, 0, 0;
  p.b_eq << 0, 0;  // x1 = x2, twice
  p.ineq_count = 5;
  p.A_in << -1, 0, -1, 0, 0, -1, -1, -1, -2, -2;
  p.b_in << -1, -1, -1, -2, -4;  // x1 ≤ 1 (twice), x2 ≤ 1, x1 + x2 ≤ 2 (twice, scaled)
  QpSolver solver(2, 3, 5);
  ASSERT_EQ(solver.solve(p), QpStatus::optimal);
  EXPECT_NEAR(solver.x()[0], 1.0, 1e-12);
  EXPECT_NEAR(solver.x()[1], 1.0, 1e-12);
  expect_kkt(p, solver, 1e-9, "degenerate");
}

TEST(QpSolver, ContradictoryConstraintsAreInfeasible) {
  QpSolver solver(2, 2, 2);
  {  // x1 ≥ 1 and x1 ≤ 0
    QpProblem p(2, 2, 2);
    p.ineq_count = 2;
    p.A_in << 1, 0, -1, 0;
    p.b_in << 1, 0;
    EXPECT_EQ(solver.solve(p), QpStatus::infeasible);
    EXPECT_TRUE(solver.x().allFinite());
  }
  {  // x1 + x2 = 1 and x1 + x2 = 2
    QpProblem p(2, 2, 2);
    p.eq_count = 2;
    p.A_eq << 1, 1, 1, 1;
    p.b_eq << 1, 2;
    EXPECT_EQ(solver.solve(p), QpStatus::infeasible);
    EXPECT_TRUE(solver.x().allFinite());
  }
  {  // x1 + x2 = 3 inside the box [0, 1]²
    QpProblem p(2, 2, 2);
    p.eq_count = 1;
    p.A_eq.row(0) << 1, 1;
    p.b_eq[0] = 3;
    p.lower.setZero();
    p.upper.setOnes();
    EXPECT_EQ(solver.solve(p), QpStatus::infeasible);
    EXPECT_TRUE(solver.x().allFinite());
  }
}

TEST(QpSolver, BadInputIsReportedNotSolved) {
  QpSolver solver(2, 0, 1);
  QpProblem p(2, 0, 1);
  p.H << 1, 0, 0, -1;  // indefinite
  EXPECT_EQ(solver.solve(p), QpStatus::invalid_input);
  p.H.setIdentity();
  p.g[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(solver.solve(p), QpStatus::invalid_input);
  p.g.setZero();
  p.lower[0] = kInf;
  EXPECT_EQ(solver.solve(p), QpStatus::invalid_input);
  p.lower[0] = -kInf;
  EXPECT_EQ(solver.solve(p), QpStatus::optimal);
  EXPECT_TRUE(solver.x().allFinite());
}

TEST(QpSolver, IterationBoundStopsTheSolve) {
  std::mt19937 rng(3);
  QpProblem p(7, 6, 30);
  random_problem(rng, p, 0, 30, true);
  p.g *= 50;  // far from the feasible region: many constraints to add
  QpSolver solver(7, 6, 30);
  solver.set_max_iterations(1);
  EXPECT_EQ(solver.solve(p), QpStatus::max_iterations);
  EXPECT_TRUE(solver.x().allFinite());
  solver.set_max_iterations(0);  // automatic bound
  EXPECT_EQ(solver.solve(p), QpStatus::optimal);
}

TEST(QpSolver, InactiveRowsAndUnboundedBoxAreIgnored) {
  QpProblem p(3, 1, 4);
  p.g << -1, -2, -3;
  p.ineq_count = 4;  // rows left at b = −inf never bind
  QpSolver solver(3, 1, 4);
  ASSERT_EQ(solver.solve(p), QpStatus::optimal);
  EXPECT_LT((solver.x() - Eigen::Vector3d(1, 2, 3)).norm(), 1e-14);
  EXPECT_EQ(solver.active_inequalities(), 0);
}

}  // namespace
}  // namespace rrlab

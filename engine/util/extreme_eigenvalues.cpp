#include <rrlab/util/extreme_eigenvalues.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rrlab {

namespace {
constexpr int kBudget = 40;  // Laguerre iterations per end before the QR fallback
constexpr double kEps = std::numeric_limits<double>::epsilon();
// a Laguerre step below this fraction of x leaves an error of about its cube
// near a simple root: far below rounding, so the iteration stops there
constexpr double kEarlyStep = 1e-5;

// T = QᵀAQ tridiagonal for the n x n symmetric a (its lower triangle) by
// Householder reflections H_k = I − β u uᵀ (Golub & Van Loan, Matrix
// Computations, Algorithm 8.3.1) on a copy of the lower triangle; N fixed,
// so the loops unroll: at n ≤ 6 Eigen's blocked Tridiagonalization costs
// several times more. u is left unnormalised (u = x + sign(x₀)‖x‖e₁, so
// uᵀu = 2‖x‖(‖x‖ + |x₀|) needs no division) and A u is formed while β's
// division runs: the reflections are a chain of dependent steps, and these
// are its longest links.
template <int N>
void tridiagonalise(const ExtremeEigenvalues::Matrix& a, double* diagonal, double* sub) {
  double t[N][N];  // the lower triangle: t[i][j], j ≤ i
  for (int c = 0; c < N; ++c)
    for (int r = c; r < N; ++r) t[r][c] = a(r, c);
  for (int k = 0; k + 2 < N; ++k) {
    // u, β with H x = −sign(x₀) μ e₁ for x = t[k+1..N−1][k]
    double sigma = 0;
    for (int i = k + 2; i < N; ++i) sigma += t[i][k] * t[i][k];
    const double x0 = t[k + 1][k];
    if (sigma == 0) {  // already tridiagonal in this column
      sub[k] = x0;
      continue;
    }
    const double mu = std::sqrt(x0 * x0 + sigma);
    const double beta = 1.0 / (mu * (mu + std::abs(x0)));
    double u[N], p[N];
    u[k + 1] = x0 >= 0 ? x0 + mu : x0 - mu;
    for (int i = k + 2; i < N; ++i) u[i] = t[i][k];
    // p = β A u, w = p − (β pᵀu / 2) u, A ← A − u wᵀ − w uᵀ on the trailing block
    for (int i = k + 1; i < N; ++i) {
      double sum = 0;
      for (int j = k + 1; j < N; ++j) sum += (j <= i ? t[i][j] : t[j][i]) * u[j];
      p[i] = sum;
    }
    double pu = 0;
    for (int i = k + 1; i < N; ++i) p[i] *= beta, pu += p[i] * u[i];
    const double half = 0.5 * beta * pu;
    for (int i = k + 1; i < N; ++i) p[i] -= half * u[i];
    for (int j = k + 1; j < N; ++j)
      for (int i = j; i < N; ++i) t[i][j] = t[i][j] - u[i] * p[j] - p[i] * u[j];
    sub[k] = x0 >= 0 ? -mu : mu;
  }
  sub[N - 2] = t[N - 1][N - 2];
  for (int k = 0; k < N; ++k) diagonal[k] = t[k][k];
}

// p(x) = det(T − xI) and its first two derivatives at x, by the three-term
// recurrence of the leading minors.
template <int N>
void characteristic(const double* diagonal, const double* off_squared, double x, double& p, double& dp, double& ddp) {
  double p0 = 1, p1 = diagonal[0] - x;  // p_{k-1}, p_k
  double d0 = 0, d1 = -1;               // their first derivatives
  double s0 = 0, s1 = 0;                // and second
  for (int k = 1; k < N; ++k) {
    const double c = diagonal[k] - x, e2 = off_squared[k - 1];
    const double p2 = c * p1 - e2 * p0;
    const double d2 = c * d1 - p1 - e2 * d0;
    const double s2 = c * s1 - 2 * d1 - e2 * s0;
    p0 = p1, p1 = p2, d0 = d1, d1 = d2, s0 = s1, s1 = s2;
  }
  p = p1, dp = d1, ddp = s1;
}

// One end's Laguerre iteration (exact for (x − c)ⁿ, so it reaches a root
// across a large gap at once; cubic near a simple root), advanced one step
// at a time so that the two ends interleave.
struct LaguerreEnd {
  double x;          // the iterate: outside the spectrum, on its side
  double direction;  // −1: the largest root from above, +1: the smallest from below
  double early;      // stop at a step below early · |x| (0: where rounding stops it)
  int iterations = 0;
  bool done = false, failed = false;

  // One step from p, p', p'' at x.
  void step(int n, double p, double dp, double ddp) {
    if (done) return;
    if (iterations++ >= kBudget) {
      done = failed = true;
      return;
    }
    if (p == 0) {  // on a root
      done = true;
      return;
    }
    const double g = dp / p, h = g * g - ddp / p;
    const double root_term = std::sqrt(std::max(0.0, (n - 1) * (n * h - g * g)));
    // the denominator of larger magnitude: the step to the nearest root
    const double denominator = g >= 0 ? g + root_term : g - root_term;
    if (denominator == 0 || !std::isfinite(denominator)) {
      done = failed = true;
      return;
    }
    const double s = -n / denominator;  // x_next = x + s
    if (!(s * direction > 0)) {  // no move towards the root: rounding has the last word
      done = true;
      return;
    }
    x += s;
    // converged: the step is below `early` of x, below the rounding of x, or
    // far below what any method resolves near 0 (ε of T's scale, 1 here):
    // the rounding of p there keeps proposing steps of 1e-20 in one direction
    if (std::abs(s) <= std::max(early, 2 * kEps) * std::abs(x) + 1e-3 * kEps) done = true;
  }
};

// The negative pivots of the LDLᵀ of T − xI (Sylvester's law of inertia):
// the eigenvalues of T below x. Backward stable.
template <int N>
int count_below(const double* diagonal, const double* off_squared, double x) {
  int count = 0;
  double pivot = 1;
  for (int k = 0; k < N; ++k) {
    pivot = diagonal[k] - x - (k > 0 ? off_squared[k - 1] / pivot : 0.0);
    if (pivot == 0) pivot = -kEps * kEps;  // a zero pivot counts as just negative (the usual convention)
    count += pivot < 0;
  }
  return count;
}

// The ends of T's spectrum (T scaled to entries of at most 1) into lo, hi;
// false when Laguerre or the Sturm counts do not settle them.
template <int N>
bool extreme_roots(const double* d, const double* e2, const double* sub, double& lo, double& hi, int& iterations) {
  // Gershgorin bounds of the spectrum
  double lower = std::numeric_limits<double>::infinity(), upper = -lower;
  for (int k = 0; k < N; ++k) {
    const double r = (k > 0 ? std::abs(sub[k - 1]) : 0.0) + (k < N - 1 ? std::abs(sub[k]) : 0.0);
    lower = std::min(lower, d[k] - r);
    upper = std::max(upper, d[k] + r);
  }
  // a positive definite T (all pivots of its LDLᵀ positive: Sylvester) has
  // 0 below its spectrum: a start far nearer the smallest eigenvalue of an
  // ill-conditioned J Jᵀ than Gershgorin's bound
  double pivot = d[0];
  bool definite = pivot > 0;
  for (int k = 1; k < N && definite; ++k) {
    pivot = d[k] - e2[k - 1] / pivot;
    definite = pivot > 0;
  }
  if (definite) lower = 0;
  // both ends at once: two independent recurrences per step keep the
  // processor busy where one waits on its own results
  LaguerreEnd high{upper, -1.0, kEarlyStep}, low{lower, +1.0, kEarlyStep};
  while (!(high.done && low.done)) {
    double p[2], dp[2], ddp[2];
    characteristic<N>(d, e2, high.x, p[0], dp[0], ddp[0]);
    characteristic<N>(d, e2, low.x, p[1], dp[1], ddp[1]);
    high.step(N, p[0], dp[0], ddp[0]);
    low.step(N, p[1], dp[1], ddp[1]);
  }
  // each end checked by Sturm counts (backward stable, unlike p(x) near a
  // double root, which it resolves only to √ε): exactly one side of
  // x ± δ, δ a few ε of T's scale (1), holds the end. An end stopped early
  // that they do not confirm goes on to where rounding stops it.
  const double delta = 16 * kEps * std::max(1.0, std::max(std::abs(upper), std::abs(lower)));
  const auto confirmed = [&](const LaguerreEnd& end) {
    return end.direction < 0
               ? count_below<N>(d, e2, end.x + delta) == N && count_below<N>(d, e2, end.x - delta) < N
               : count_below<N>(d, e2, end.x - delta) == 0 && count_below<N>(d, e2, end.x + delta) > 0;
  };
  for (LaguerreEnd* end : {&high, &low}) {
    if (end->failed) return false;
    if (confirmed(*end)) continue;
    end->early = 0, end->done = false;
    while (!end->done) {
      double p, dp, ddp;
      characteristic<N>(d, e2, end->x, p, dp, ddp);
      end->step(N, p, dp, ddp);
    }
    if (end->failed || !confirmed(*end)) return false;
  }
  lo = low.x, hi = high.x;
  iterations = low.iterations + high.iterations;
  return true;
}

template <int N>
bool compute_fixed(const ExtremeEigenvalues::Matrix& a, double& min, double& max, int& iterations) {
  double d[N], sub[N - 1], e2[N - 1];
  tridiagonalise<N>(a, d, sub);
  // T scaled to entries of at most 1: det(T − xI) stays far from overflow
  double scale = 0, sum = 0;  // sum: NaN or ±inf when any entry is (max skips NaN)
  for (int k = 0; k < N; ++k) scale = std::max(scale, std::abs(d[k])), sum += d[k];
  for (int k = 0; k < N - 1; ++k) scale = std::max(scale, std::abs(sub[k])), sum += sub[k];
  if (!(scale > 0) || !std::isfinite(scale) || !std::isfinite(sum)) return false;  // zero, or not finite
  for (int k = 0; k < N; ++k) d[k] /= scale;
  for (int k = 0; k < N - 1; ++k) sub[k] /= scale, e2[k] = sub[k] * sub[k];
  double lo = 0, hi = 0;
  if (!extreme_roots<N>(d, e2, sub, lo, hi, iterations)) return false;
  min = lo * scale, max = hi * scale;
  return true;
}
}  // namespace

ExtremeEigenvalues::ExtremeEigenvalues(int size) : fallback_(size) {}

void ExtremeEigenvalues::compute(const Matrix& a) {
  const int n = int(a.rows());
  iterations_ = 0;
  bool settled = false;
  switch (n) {
    case 1: min_ = max_ = a(0, 0); return;
    case 2: settled = compute_fixed<2>(a, min_, max_, iterations_); break;
    case 3: settled = compute_fixed<3>(a, min_, max_, iterations_); break;
    case 4: settled = compute_fixed<4>(a, min_, max_, iterations_); break;
    case 5: settled = compute_fixed<5>(a, min_, max_, iterations_); break;
    case 6: settled = compute_fixed<6>(a, min_, max_, iterations_); break;
  }
  if (!settled) {  // the QR solver says what it is
    fallback_.compute(a, Eigen::EigenvaluesOnly);
    min_ = fallback_.eigenvalues()[0], max_ = fallback_.eigenvalues()[n - 1];
    iterations_ = -1;
  }
}

}  // namespace rrlab

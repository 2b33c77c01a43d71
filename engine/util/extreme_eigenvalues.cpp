#include "util/extreme_eigenvalues.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rrlab {

namespace {
constexpr int kBudget = 40;  // Laguerre iterations per end before the QR fallback
constexpr double kEps = std::numeric_limits<double>::epsilon();
}  // namespace

ExtremeEigenvalues::ExtremeEigenvalues(int size)
    : tridiagonal_(size), diagonal_(size), off_squared_(size), fallback_(size) {}

void ExtremeEigenvalues::compute(const Matrix& a) {
  const int n = int(a.rows());
  iterations_ = 0;
  if (n == 1) {
    min_ = max_ = a(0, 0);
    return;
  }
  tridiagonal_.compute(a);
  // T scaled to entries of at most 1: det(T − xI) stays far from overflow
  const auto sub = tridiagonal_.subDiagonal();
  double scale = tridiagonal_.diagonal().cwiseAbs().maxCoeff();
  scale = std::max(scale, sub.cwiseAbs().maxCoeff());
  if (!(scale > 0) || !std::isfinite(scale)) {  // zero, or not finite: the QR solver says what it is
    fallback_.compute(a, Eigen::EigenvaluesOnly);
    min_ = fallback_.eigenvalues()[0], max_ = fallback_.eigenvalues()[n - 1];
    iterations_ = -1;
    return;
  }
  diagonal_ = tridiagonal_.diagonal() / scale;
  off_squared_.resize(n - 1);
  for (int k = 0; k < n - 1; ++k) off_squared_[k] = (sub[k] / scale) * (sub[k] / scale);
  // Gershgorin bounds of the spectrum
  double lower = std::numeric_limits<double>::infinity(), upper = -lower;
  for (int k = 0; k < n; ++k) {
    const double r = (k > 0 ? std::abs(sub[k - 1]) : 0.0) / scale + (k < n - 1 ? std::abs(sub[k]) : 0.0) / scale;
    lower = std::min(lower, diagonal_[k] - r);
    upper = std::max(upper, diagonal_[k] + r);
  }
  // a positive definite T (all pivots of its LDLᵀ positive: Sylvester) has
  // 0 below its spectrum: a start far nearer the smallest eigenvalue of an
  // ill-conditioned J Jᵀ than Gershgorin's bound
  double pivot = diagonal_[0];
  bool definite = pivot > 0;
  for (int k = 1; k < n && definite; ++k) {
    pivot = diagonal_[k] - off_squared_[k - 1] / pivot;
    definite = pivot > 0;
  }
  if (definite) lower = 0;
  double lo = 0, hi = 0;
  int it_lo = 0, it_hi = 0;
  // each end checked by Sturm counts (backward stable, unlike p(x) near a
  // double root, which it resolves only to √ε): exactly one side of
  // x ± δ, δ a few ε of T's scale (1), holds the end
  const double delta = 16 * kEps * std::max(1.0, std::max(std::abs(upper), std::abs(lower)));
  const bool settled = laguerre(upper, -1.0, hi, it_hi) && laguerre(lower, +1.0, lo, it_lo) &&
                       count_below(hi + delta) == n && count_below(hi - delta) < n &&
                       count_below(lo - delta) == 0 && count_below(lo + delta) > 0;
  if (!settled) {
    fallback_.compute(a, Eigen::EigenvaluesOnly);
    min_ = fallback_.eigenvalues()[0], max_ = fallback_.eigenvalues()[n - 1];
    iterations_ = -1;
    return;
  }
  min_ = lo * scale, max_ = hi * scale;
  iterations_ = it_lo + it_hi;
}

int ExtremeEigenvalues::count_below(double x) const {
  // the negative pivots of the LDLᵀ of T − xI (Sylvester's law of inertia)
  const int n = int(diagonal_.size());
  int count = 0;
  double pivot = 1;
  for (int k = 0; k < n; ++k) {
    pivot = diagonal_[k] - x - (k > 0 ? off_squared_[k - 1] / pivot : 0.0);
    if (pivot == 0) pivot = -kEps * kEps;  // a zero pivot counts as just negative (the usual convention)
    count += pivot < 0;
  }
  return count;
}

bool ExtremeEigenvalues::laguerre(double x, double direction, double& root, int& iterations) const {
  // Laguerre's iteration (exact for (x − c)ⁿ, so it reaches a root across a
  // large gap at once; cubic near a simple root) on p(x) = det(T − xI),
  // with p, p', p'' by the three-term recurrence of the leading minors
  const int n = int(diagonal_.size());
  for (iterations = 0; iterations < kBudget; ++iterations) {
    double p0 = 1, p1 = diagonal_[0] - x;  // p_{k-1}, p_k
    double d0 = 0, d1 = -1;                // their first derivatives
    double s0 = 0, s1 = 0;                 // and second
    for (int k = 1; k < n; ++k) {
      const double c = diagonal_[k] - x, e2 = off_squared_[k - 1];
      const double p2 = c * p1 - e2 * p0;
      const double d2 = c * d1 - p1 - e2 * d0;
      const double s2 = c * s1 - 2 * d1 - e2 * s0;
      p0 = p1, p1 = p2, d0 = d1, d1 = d2, s0 = s1, s1 = s2;
    }
    if (p1 == 0) {  // on a root
      root = x;
      return true;
    }
    const double g = d1 / p1, h = g * g - s1 / p1;
    const double root_term = std::sqrt(std::max(0.0, (n - 1) * (n * h - g * g)));
    // the denominator of larger magnitude: the step to the nearest root
    const double denominator = g >= 0 ? g + root_term : g - root_term;
    if (denominator == 0 || !std::isfinite(denominator)) return false;
    const double step = -n / denominator;  // x_next = x + step
    if (!(step * direction > 0)) {  // no move towards the root: rounding has the last word
      root = x;
      return true;
    }
    x += step;
    // converged: the step is below the rounding of x, or far below what any
    // method resolves near 0 (ε of T's scale, 1 here): the rounding of p
    // there keeps proposing steps of 1e-20 in one direction
    if (std::abs(step) <= 2 * kEps * std::abs(x) + 1e-3 * kEps) {
      root = x;
      return true;
    }
  }
  return false;
}

}  // namespace rrlab

#include <rrlab/sweep/sweep_stats.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rrlab::sweep {

Interval wilson_interval(size_t successes, size_t n, double z) {
  if (n == 0) return {0, 1};
  const double nn = double(n), p = double(successes) / nn, z2 = z * z;
  const double denominator = 1 + z2 / nn;
  const double centre = (p + z2 / (2 * nn)) / denominator;
  const double half = z * std::sqrt(p * (1 - p) / nn + z2 / (4 * nn * nn)) / denominator;
  // exact at the ends: centre - half is 0 for no success only up to rounding (5.6e-17 for 0 of 3)
  return {successes == 0 ? 0.0 : std::max(0.0, centre - half), successes == n ? 1.0 : std::min(1.0, centre + half)};
}

double quantile(std::vector<double> values, double q) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const double h = (double(values.size()) - 1) * q;
  const size_t lo = size_t(std::floor(h));
  const size_t hi = std::min(lo + 1, values.size() - 1);
  return values[lo] + (h - double(lo)) * (values[hi] - values[lo]);
}

double mcnemar_exact_p(size_t b, size_t c) {
  const size_t n = b + c, k = std::min(b, c);
  if (n == 0) return 1.0;
  // sum of C(n, i) / 2^n for i <= k, in logs (n may be thousands)
  const double log_half_n = double(n) * std::log(0.5);
  const double log_n_fact = std::lgamma(double(n) + 1);
  double tail = 0;
  for (size_t i = 0; i <= k; ++i)
    tail += std::exp(log_n_fact - std::lgamma(double(i) + 1) - std::lgamma(double(n - i) + 1) + log_half_n);
  return std::min(1.0, 2 * tail);
}

double shifted_geometric_mean(const std::vector<double>& values, double shift) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  double log_sum = 0;
  for (double v : values) log_sum += std::log(std::max(v, 0.0) + shift);
  return std::exp(log_sum / double(values.size())) - shift;
}

}  // namespace rrlab::sweep

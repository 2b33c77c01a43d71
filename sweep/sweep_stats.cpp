#include "sweep/sweep_stats.hpp"

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
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

double quantile(std::vector<double> values, double q) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const double h = (double(values.size()) - 1) * q;
  const size_t lo = size_t(std::floor(h));
  const size_t hi = std::min(lo + 1, values.size() - 1);
  return values[lo] + (h - double(lo)) * (values[hi] - values[lo]);
}

}  // namespace rrlab::sweep

#include <rrlab/sweep/sweep_power.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace rrlab::sweep {

namespace {

constexpr double kZAlpha = 1.959963984540054;   // z_{1 - 0.05 / 2}
constexpr double kZPower = 0.8416212335729143;  // z_{0.8}
constexpr size_t kFewestRejecting = 6;          // 2 / 2^6 < 0.05 <= 2 / 2^5

// The exact sum's reach: n psi <= kExactDiscordant keeps every d it sums
// below n psi + 12 sqrt(n psi) + 2 < kCriticalCounts.
constexpr size_t kCriticalCounts = 1500;

// k_d for every d < kCriticalCounts: the largest k with 2 P(Bin(d, 1/2) <= k)
// < alpha, -1 where no k qualifies. Built once (about kCriticalCounts^2 / 4 steps).
const std::vector<int>& critical_counts() {
  static const std::vector<int> table = [] {
    std::vector<int> k(kCriticalCounts, -1);
    for (size_t d = 1; d < kCriticalCounts; ++d) {
      // from the middle term down (2^-d underflows past d = 1074): C(d, i) / 2^d in logs, then by ratio
      const size_t mid = d / 2;
      double term = std::exp(std::lgamma(double(d) + 1) - std::lgamma(double(mid) + 1) -
                             std::lgamma(double(d - mid) + 1) - double(d) * std::log(2.0));
      std::vector<double> terms(mid + 1);
      for (size_t i = mid + 1; i-- > 0;) {
        terms[i] = term;
        term *= double(i) / double(d - i + 1);
      }
      double cdf = 0;
      for (size_t i = 0; i <= mid; ++i) {
        cdf += terms[i];
        if (2 * cdf >= kPowerAlpha) break;
        k[d] = int(i);
      }
    }
    return k;
  }();
  return table;
}

// log P(Binomial(d, q) = w), 0 < q < 1.
double log_term(size_t d, double q, size_t w) {
  return std::lgamma(double(d) + 1) - std::lgamma(double(w) + 1) - std::lgamma(double(d - w) + 1) +
         double(w) * std::log(q) + double(d - w) * std::log1p(-q);
}

// P(Binomial(d, q) <= k). Summed outwards from the largest term it holds
// (the mode, or k below it), each way until the terms fall below rounding:
// a start from (1 - q)^d would underflow (0.55^1400) where the tail is not small.
double lower_tail(size_t d, double q, int k) {
  if (k < 0) return 0;
  if (q <= 0 || size_t(k) >= d) return 1;
  if (q >= 1) return 0;
  const size_t mode = std::min(d, size_t(std::floor(double(d + 1) * q))), top = std::min(size_t(k), mode);
  const double start = std::exp(log_term(d, q, top)), down = (1 - q) / q, up = q / (1 - q);
  double sum = start, term = start;
  for (size_t w = top; w > 0 && term > 1e-17 * sum; --w) {  // w to w - 1
    term *= double(w) / double(d - w + 1) * down;
    sum += term;
  }
  term = start;
  for (size_t w = top; w < size_t(k) && term > 1e-17 * sum; ++w) {  // w to w + 1, past the mode
    term *= double(d - w) / double(w + 1) * up;
    sum += term;
  }
  return std::min(1.0, sum);
}

// n psi <= kExactDiscordant (mcnemar_power).
double exact_power(size_t n, double psi, double delta) {
  const std::vector<int>& k = critical_counts();
  const double q = std::clamp((psi + delta) / (2 * psi), 0.0, 1.0);
  const auto rejection = [&](size_t d) { return lower_tail(d, q, k[d]) + lower_tail(d, 1 - q, k[d]); };
  if (psi >= 1) return k[n] < 0 ? 0 : rejection(n);
  // P(D = d) beyond 12 standard deviations of the mean is far below rounding
  const double mean = double(n) * psi, reach = 12 * std::sqrt(mean * (1 - psi)) + 2;
  const size_t first = size_t(std::max(double(kFewestRejecting), std::floor(mean - reach)));
  const size_t last = std::min(n, size_t(std::ceil(mean + reach)));
  const double log_n = std::lgamma(double(n) + 1), log_psi = std::log(psi), log_rest = std::log1p(-psi);
  double power = 0;
  for (size_t d = first; d <= last; ++d) {
    if (k[d] < 0) continue;
    const double p_d = std::exp(log_n - std::lgamma(double(d) + 1) - std::lgamma(double(n - d) + 1) +
                                double(d) * log_psi + double(n - d) * log_rest);
    if (p_d < 1e-16) continue;  // below the sum's own rounding
    power += p_d * rejection(d);
  }
  return std::min(1.0, power);
}

double normal_power(size_t n, double psi, double delta) {
  const double spread = psi - delta * delta;
  if (spread <= 0) return delta > 0 ? 1 : 0;
  const double x = (delta * std::sqrt(double(n)) - kZAlpha * std::sqrt(psi)) / std::sqrt(spread);
  return 0.5 * std::erfc(-x / std::sqrt(2.0));
}

}  // namespace

double mcnemar_power(size_t n, double psi, double delta) {
  psi = std::clamp(psi, 0.0, 1.0);
  delta = std::clamp(delta, 0.0, psi);
  if (psi <= 0 || n < kFewestRejecting) return 0;
  return double(n) * psi <= kExactDiscordant ? exact_power(n, psi, delta) : normal_power(n, psi, delta);
}

double min_detectable_difference(size_t n, double psi) {
  psi = std::clamp(psi, 0.0, 1.0);
  const auto power = [&](double delta) { return mcnemar_power(n, std::max(psi, delta), delta); };
  if (power(1) < kPowerTarget) return std::numeric_limits<double>::infinity();
  // the power rises with delta (at a fixed discordance, and with it beyond psi): bisect
  double lo = 0, hi = 1;
  for (int i = 0; i < 24; ++i) {
    const double mid = 0.5 * (lo + hi);
    (power(mid) >= kPowerTarget ? hi : lo) = mid;
  }
  return hi;
}

size_t cases_needed(double delta, double psi) {
  delta = std::clamp(delta, 1e-6, 1.0);
  psi = std::clamp(std::max(psi, delta), 0.0, 1.0);
  const double root = (kZAlpha * std::sqrt(psi) + kZPower * std::sqrt(std::max(0.0, psi - delta * delta))) / delta;
  size_t n = std::max(kFewestRejecting, size_t(std::ceil(root * root)));
  if (double(n) * psi > kExactDiscordant) return n;
  // the exact power is not monotone in n (the test is discrete): walk from Connor's n
  while (n > kFewestRejecting && mcnemar_power(n - 1, psi, delta) >= kPowerTarget) --n;
  for (size_t steps = 0; steps < 1000 && mcnemar_power(n, psi, delta) < kPowerTarget; ++steps) ++n;
  return n;
}

}  // namespace rrlab::sweep

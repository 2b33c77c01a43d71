// The statistics sweep reports use.
#pragma once

#include <cstddef>
#include <vector>

namespace rrlab::sweep {

struct Interval {
  double low = 0, high = 0;
};

// Wilson score interval of a binomial proportion (default 95 %: z = 1.959964);
// [0, 1] when n is 0.
Interval wilson_interval(size_t successes, size_t n, double z = 1.959963984540054);

// The q-quantile (0 <= q <= 1) by linear interpolation between order
// statistics (R type 7, numpy's default): median = quantile(v, 0.5). NaN
// when `values` is empty.
double quantile(std::vector<double> values, double q);

// Exact McNemar test of paired binary outcomes: `b` pairs where only the
// first succeeded, `c` where only the second did. Two-sided p-value,
// min(1, 2 P(X <= min(b, c))) for X ~ Binomial(b + c, 1/2); 1 when b + c = 0.
double mcnemar_exact_p(size_t b, size_t c);

// Shifted geometric mean, exp(mean(log(x + shift))) - shift: a mean of times
// that neither a few slow runs nor near-zero ones dominate (NaN when empty).
double shifted_geometric_mean(const std::vector<double>& values, double shift);

}  // namespace rrlab::sweep

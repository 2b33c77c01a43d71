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

}  // namespace rrlab::sweep

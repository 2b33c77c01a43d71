#include <rrlab/sim/step_time_histogram.hpp>

#include <algorithm>
#include <cmath>

namespace rrlab {

namespace {
constexpr double kLow = 0.01, kDecades = 9.0;  // 0.01 µs .. 1e7 µs
}

void StepTimeHistogram::add(double us) {
  const double x = std::log10(std::max(us, kLow) / kLow) / kDecades;
  const int bin = std::clamp(static_cast<int>(x * kBins), 0, kBins - 1);
  ++counts_[bin];
  ++total_;
  sum_ += us;
}

StepTimeStats StepTimeHistogram::stats() const {
  StepTimeStats s;
  if (total_ == 0) return s;
  s.mean = sum_ / double(total_);
  auto percentile = [&](double fraction) {
    const auto rank = static_cast<std::uint64_t>(std::ceil(fraction * double(total_)));
    std::uint64_t seen = 0;
    for (int b = 0; b < kBins; ++b) {
      seen += counts_[b];
      if (seen >= rank) return kLow * std::pow(10.0, (b + 0.5) / kBins * kDecades);  // bin centre
    }
    return 0.0;
  };
  s.p50 = percentile(0.5);
  s.p99 = percentile(0.99);
  return s;
}

void StepTimeHistogram::clear() {
  counts_.fill(0);
  total_ = 0;
  sum_ = 0;
}

}  // namespace rrlab

// Percentiles of step compute times without storing every sample:
// log-spaced bins from 0.01 µs to 10 s (about 1% resolution).
#pragma once

#include <array>
#include <cstdint>

#include <rrlab/sim/frame.hpp>

namespace rrlab {

class StepTimeHistogram {
 public:
  void add(double us);
  StepTimeStats stats() const;
  void clear();

 private:
  static constexpr int kBins = 2048;
  std::array<std::uint64_t, kBins> counts_{};
  std::uint64_t total_ = 0;
  double sum_ = 0;
};

}  // namespace rrlab

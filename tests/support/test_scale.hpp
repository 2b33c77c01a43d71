// How many generated cases a long suite checks. `make test` (and CI) runs a
// sample, so that it stays within its time budget; `make test-scale` sets
// RRLAB_TEST_SCALE=full and runs every case (docs/testing.md, "What runs where").
#pragma once

#include <cstdlib>
#include <string_view>

namespace rrlab::test {

inline bool full_scale() {
  const char* scale = std::getenv("RRLAB_TEST_SCALE");
  return scale && std::string_view(scale) == "full";
}

// `full` cases under make test-scale, `sample` otherwise.
inline int scale_cases(int full, int sample) { return full_scale() ? full : sample; }

}  // namespace rrlab::test

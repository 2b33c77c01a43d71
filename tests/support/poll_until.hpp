// The one polling loop of the tests: evaluate a condition until it holds or a
// deadline passes. Without gtest, so the test support library (the server
// process, the soak and the load tests link it) can use it; gtest tests call
// eventually() (eventually.hpp), which reports a timeout as a failure.
#pragma once

#include <algorithm>
#include <chrono>
#include <functional>
#include <thread>

namespace rrlab::test {

// True once `condition` holds; false when `timeout` passes first. Polls at 1,
// 2, 4, ... ms, then every 50 ms: a fast machine returns at once.
inline bool poll_until(const std::function<bool()>& condition, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (auto pause = std::chrono::milliseconds(1);; pause = std::min(pause * 2, std::chrono::milliseconds(50))) {
    if (condition()) return true;
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(pause);
  }
}

}  // namespace rrlab::test

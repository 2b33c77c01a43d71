// Waiting in tests: poll a condition until it holds or a deadline passes,
// never a fixed sleep. The timeout is an upper bound for slow or busy
// machines (sanitizers, a loaded CI core); a fast machine returns at once.
#pragma once

#include <chrono>
#include <functional>
#include <string>
#include <thread>

#include <gtest/gtest.h>

namespace rrlab::test {

// True once `condition` holds; false (and a test failure naming `what`) when
// `timeout` passes first. Polls every few milliseconds.
inline bool eventually(const std::function<bool()>& condition, std::chrono::milliseconds timeout,
                       const std::string& what) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (auto pause = std::chrono::milliseconds(1);; pause = std::min(pause * 2, std::chrono::milliseconds(50))) {
    if (condition()) return true;
    if (std::chrono::steady_clock::now() >= deadline) break;
    std::this_thread::sleep_for(pause);
  }
  ADD_FAILURE() << "timed out after " << timeout.count() << " ms waiting for: " << what;
  return false;
}

}  // namespace rrlab::test

// Waiting in tests: poll a condition until it holds or a deadline passes,
// never a fixed sleep. The timeout is an upper bound for slow or busy
// machines (sanitizers, a loaded CI core); a fast machine returns at once.
// A test may sleep only where it is about time itself (a pace of input, a
// slow destructor, a window in which it samples), says so in a comment, and
// then asserts only upper bounds on what the clock gives.
#pragma once

#include <chrono>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "support/poll_until.hpp"

namespace rrlab::test {

// True once `condition` holds; false (and a test failure naming `what`) when
// `timeout` passes first. Polls every few milliseconds (poll_until.hpp).
inline bool eventually(const std::function<bool()>& condition, std::chrono::milliseconds timeout,
                       const std::string& what) {
  if (poll_until(condition, timeout)) return true;
  ADD_FAILURE() << "timed out after " << timeout.count() << " ms waiting for: " << what;
  return false;
}

}  // namespace rrlab::test

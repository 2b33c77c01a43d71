// RRLAB_CHECK(condition, message): a check of user input that stays in every
// build. When `condition` is false it throws std::invalid_argument naming the
// function, the message and the condition's text; it cannot be disabled
// (NDEBUG, which Release defines, removes assert() but not this).
//
// The rule (as Drake's DRAKE_THROW_UNLESS / DRAKE_ASSERT):
//  - RRLAB_CHECK where a public entry point takes input that its caller
//    chooses: sizes of vectors and matrices handed to kinematics, indices
//    into a model, values from a scenario or a request. A wrong value there
//    is the caller's mistake and must be a clear error, never undefined
//    behaviour in a Release build.
//  - assert() for the engine's own invariants: what engine code guarantees to
//    itself (a support edge found, a buffer sized by the engine from a task
//    space, as in util/small_lu.hpp and util/right_inverse.cpp), checked in
//    Debug and sanitizer builds, free in Release's innermost loops.
// `message` is any expression convertible to std::string; it is evaluated
// only when the check fails, so it may format numbers.
#pragma once

#include <stdexcept>
#include <string>

namespace rrlab::detail {

[[noreturn, gnu::cold, gnu::noinline]] inline void check_failed(const char* function, const std::string& message,
                                                                const char* condition) {
  throw std::invalid_argument(std::string(function) + ": " + message + " (check failed: " + condition + ")");
}

}  // namespace rrlab::detail

#define RRLAB_CHECK(condition, message)                                  \
  do {                                                                   \
    if (!(condition)) [[unlikely]]                                       \
      ::rrlab::detail::check_failed(__func__, (message), #condition);    \
  } while (false)

// net/auth_throttle: wrong tokens per address within a window, with given times.
#include <rrlab/server/net/auth_throttle.hpp>

#include <gtest/gtest.h>

namespace rrlab::server {
namespace {

using std::chrono::seconds;

TEST(AuthThrottle, BlocksAnAddressForTheRestOfItsWindow) {
  AuthThrottle throttle(3, seconds(60));
  const auto t0 = AuthThrottle::Clock::time_point{} + seconds(1000);
  for (int i = 0; i < 2; ++i) throttle.failed("10.0.0.1", t0 + seconds(i));
  EXPECT_EQ(throttle.blocked_for("10.0.0.1", t0 + seconds(2)), 0);  // two of three
  throttle.failed("10.0.0.1", t0 + seconds(2));
  EXPECT_EQ(throttle.blocked_for("10.0.0.1", t0 + seconds(2)), 58);  // the window began at t0
  EXPECT_EQ(throttle.blocked_for("10.0.0.1", t0 + std::chrono::milliseconds(59'500)), 1);  // rounded up
  EXPECT_EQ(throttle.blocked_for("10.0.0.2", t0 + seconds(2)), 0);  // another address
  EXPECT_EQ(throttle.blocked_for("10.0.0.1", t0 + seconds(60)), 0);  // the window ended
  throttle.failed("10.0.0.1", t0 + seconds(61));  // a new window, one failure
  EXPECT_EQ(throttle.blocked_for("10.0.0.1", t0 + seconds(61)), 0);
}

TEST(AuthThrottle, KeepsABoundedNumberOfAddresses) {
  AuthThrottle throttle(1, seconds(60), 3);
  const auto t0 = AuthThrottle::Clock::time_point{} + seconds(1000);
  for (int i = 0; i < 3; ++i) throttle.failed("a" + std::to_string(i), t0 + seconds(i));
  EXPECT_GT(throttle.blocked_for("a0", t0 + seconds(3)), 0);
  throttle.failed("b", t0 + seconds(3));  // all current: the oldest (a0) goes
  EXPECT_EQ(throttle.blocked_for("a0", t0 + seconds(3)), 0);
  EXPECT_GT(throttle.blocked_for("a1", t0 + seconds(3)), 0);
  EXPECT_GT(throttle.blocked_for("b", t0 + seconds(3)), 0);
}

}  // namespace
}  // namespace rrlab::server

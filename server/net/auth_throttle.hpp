// Answers repeated wrong tokens cheaply: an address that sent `limit` wrong
// tokens within `window` gets 429 with Retry-After for every further wrong
// token until that window ends. The right token always passes, so that a
// guesser sharing the holder's address (every local process shares
// 127.0.0.1) cannot lock the holder out; what makes guessing infeasible is
// the token's length (at least 16 characters: docs/api.md, Access). Requests
// without a token are not affected. Plain types, no Beast: the rule is tested
// with given times.
#pragma once

#include <chrono>
#include <cstddef>
#include <map>
#include <mutex>
#include <string>

namespace rrlab::server {

class AuthThrottle {
 public:
  using Clock = std::chrono::steady_clock;
  explicit AuthThrottle(int limit = 20, std::chrono::seconds window = std::chrono::seconds(60),
                        std::size_t max_addresses = 4096)
      : limit_(limit), window_(window), max_addresses_(max_addresses) {}

  // Seconds until `address` may try again (rounded up); 0: not blocked.
  long blocked_for(const std::string& address, Clock::time_point now);
  // `address` sent a wrong token.
  void failed(const std::string& address, Clock::time_point now);

 private:
  struct Window {
    Clock::time_point start;
    int failures = 0;
  };
  const int limit_;
  const std::chrono::seconds window_;
  // beyond this many addresses, windows that ended are dropped; if all are
  // current, the oldest goes (memory stays bounded whatever the peers do)
  const std::size_t max_addresses_;
  std::mutex mutex_;
  std::map<std::string, Window> windows_;
};

}  // namespace rrlab::server

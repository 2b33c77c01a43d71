// Slows down token guessing: an address that sent `limit` wrong tokens within
// `window` is refused (429 with Retry-After) for every request that carries a
// token, right or wrong, until that window ends, so that a guess answers
// nothing either way. Requests without a token (static files, health) are not
// affected. Plain types, no Beast: the rule is tested with given times.
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

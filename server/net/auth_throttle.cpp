#include <rrlab/server/net/auth_throttle.hpp>

#include <algorithm>

namespace rrlab::server {

long AuthThrottle::blocked_for(const std::string& address, Clock::time_point now) {
  std::lock_guard lock(mutex_);
  const auto it = windows_.find(address);
  if (it == windows_.end() || it->second.failures < limit_) return 0;
  const auto left = it->second.start + window_ - now;
  if (left <= Clock::duration::zero()) return 0;
  return std::max<long>(1, long(std::chrono::ceil<std::chrono::seconds>(left).count()));
}

void AuthThrottle::failed(const std::string& address, Clock::time_point now) {
  std::lock_guard lock(mutex_);
  auto it = windows_.find(address);
  if (it == windows_.end()) {
    if (windows_.size() >= max_addresses_) {
      for (auto w = windows_.begin(); w != windows_.end();)
        w = now - w->second.start >= window_ ? windows_.erase(w) : std::next(w);
      if (windows_.size() >= max_addresses_)
        windows_.erase(std::min_element(windows_.begin(), windows_.end(), [](const auto& a, const auto& b) {
          return a.second.start < b.second.start;
        }));
    }
    it = windows_.emplace(address, Window{now, 0}).first;
  }
  Window& w = it->second;
  if (now - w.start >= window_) w = Window{now, 0};
  ++w.failures;
}

}  // namespace rrlab::server

// What a WebSocket session streams: a live run lane or a replay. The session
// sends snapshot() on connect and, whenever the published scene_version
// passes the one it sent, what changed (update_since: a params or scene
// message, or a whole snapshot), then the latest published frame at its
// display rate (latest wins). The messages its clients send are parsed by
// the routes (routes/socket_message.hpp), which steer the source they name
// (a live lane: app/lane_source.hpp; a replay: app/replay_player.hpp).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace rrlab::server {

class Controller;

struct PublishedFrame {
  std::uint64_t version = 0;  // increases with every publication
  std::uint64_t scene_version = 0;
  std::shared_ptr<const std::string> text;
};

// Callbacks told when a new frame is published (sessions post to their own
// strand from there, so a publication reaches every client at once).
class Subscribers {
 public:
  std::uint64_t add(std::function<void()> notify) {
    std::lock_guard lock(mutex_);
    callbacks_[++next_] = std::move(notify);
    return next_;
  }
  void remove(std::uint64_t id) {
    std::lock_guard lock(mutex_);
    callbacks_.erase(id);
  }
  std::size_t size() {
    std::lock_guard lock(mutex_);
    return callbacks_.size();
  }
  bool ever_added() {
    std::lock_guard lock(mutex_);
    return next_ > 0;
  }
  void notify_all() {
    std::vector<std::function<void()>> callbacks;  // called unlocked: a callback may remove itself
    {
      std::lock_guard lock(mutex_);
      for (auto& [id, notify] : callbacks_) callbacks.push_back(notify);
    }
    for (auto& notify : callbacks) notify();
  }

 private:
  std::mutex mutex_;
  std::map<std::uint64_t, std::function<void()>> callbacks_;
  std::uint64_t next_ = 0;
};

// What brings a client from one scene version to the current one: the
// messages to send and the version they bring it to.
struct SceneUpdate {
  std::vector<std::string> messages;
  std::uint64_t version = 0;
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  virtual Subscribers& subscribers() = 0;
  virtual std::string snapshot() = 0;
  // Everything changed since `since` (a scene_version the client has): by
  // default a whole snapshot.
  virtual SceneUpdate update_since(std::uint64_t since) {
    (void)since;
    const std::uint64_t version = latest().scene_version;
    return {{snapshot()}, version};
  }
  virtual PublishedFrame latest() = 0;
  // Who may steer (app/controller.hpp): a live run's; nullptr for a replay.
  virtual Controller* controller() { return nullptr; }
};

}  // namespace rrlab::server

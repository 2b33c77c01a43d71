// What a WebSocket session streams: a live run lane or a replay. The session
// sends snapshot() on connect and whenever scene_version() changes, then the
// latest published frame at its display rate (latest wins), and hands the
// messages it receives to handle_message().
#pragma once

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

namespace rrlab::server {

struct PublishedFrame {
  std::uint64_t version = 0;  // increases with every publication
  std::uint64_t scene_version = 0;
  std::shared_ptr<const std::string> text;
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  virtual std::string snapshot() = 0;
  virtual PublishedFrame latest() = 0;
  // A client message (inputs, control); returns the reply to send. Never throws.
  virtual nlohmann::json handle_message(const nlohmann::json& message) = 0;
};

}  // namespace rrlab::server

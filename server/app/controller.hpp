// Who steers a live run: one controller per run group. The first client that
// sends an input (or control) holds control; every other client watches and
// gets 409 "not_controller" when it tries to steer, until the holder releases
// control, disconnects, or another client takes over explicitly
// ({"type": "control", "action": "take"} on the WebSocket, or
// POST /api/runs/{id}/control {"action": "take"}), which the holder is told
// about on its WebSockets.
//
// Control is held by named clients. A client names itself with the `client`
// query parameter of its WebSocket (the dashboard sends a per-tab id) and the
// Rrlab-Client header of its REST requests (the same id, so that a tab's REST
// and WebSocket inputs are one client): 1 to 64 of [A-Za-z0-9_.-]. An unnamed
// client (curl, scripts, a WebSocket without `client`) may steer while no
// named client holds control, and never holds it. Control is released when
// the holder's last WebSocket to the run closes (a holder that only uses REST
// keeps it until it releases it or another client takes over).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>

namespace rrlab::server {

class Controller {
 public:
  using Notify = std::function<void(const nlohmann::json&)>;

  // A WebSocket connection of `client`, told of take-overs through `notify`;
  // returns the handle for detach().
  std::uint64_t attach(const std::string& client, Notify notify);
  // The connection closed: control is released when it was the holder's last one.
  void detach(std::uint64_t connection);

  // Before an input or control from `client`: takes control if nobody holds
  // it (named clients only); throws ApiError 409 "not_controller" if another
  // client holds it.
  void claim(const std::string& client);
  // `client` takes control (the previous holder is told); returns state_json.
  nlohmann::json take(const std::string& client);
  // `client` lets go (nothing if it does not hold control); returns state_json.
  nlohmann::json release(const std::string& client);
  // {"controller": "you" | "other" | "none"} as seen by `client`.
  nlohmann::json state_json(const std::string& client);

 private:
  nlohmann::json state_locked(const std::string& client) const;

  struct Connection {
    std::string client;
    Notify notify;
  };
  std::mutex mutex_;
  std::string holder_;  // empty: nobody
  std::map<std::uint64_t, Connection> connections_;
  std::uint64_t next_ = 0;
};

// A client name as accepted: 1 to 64 of [A-Za-z0-9_.-]; else empty.
std::string valid_client_name(const std::string& name);

}  // namespace rrlab::server

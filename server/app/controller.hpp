// Who steers a live run: one controller per run group. The first client that
// sends an input (or control) holds control; every other client watches and
// is refused ("not_controller", 409) when it tries to steer, until the holder releases
// control, disconnects, or another client takes over explicitly
// ({"type": "control", "action": "take"} on the WebSocket, or
// POST /api/runs/{id}/control {"action": "take"}), which the holder is told
// about on its WebSockets. Every WebSocket of the run hears who holds control
// when it connects and whenever that changes:
// {"type": "control", "event": "state", "controller": "you" | "other" | "none"}.
//
// Clients are told apart by name: the `client` query parameter of a
// WebSocket and the Rrlab-Client header of a REST request (1 to 64 of
// [A-Za-z0-9_.-]; the dashboard sends one random name per tab on both, so a
// tab's REST controls and its socket are one client). A WebSocket without a
// name is a client of its own (named after its connection). A REST request
// without a name (curl, scripts, an operator stopping a run) is not a party
// to control: it neither holds nor is refused it. Control is released when the
// holder's last WebSocket to the run closes; a holder with no WebSocket to
// the run (one that steers over REST) loses it after kRestControlLapse (60 s)
// without a request. A message or request that is refused (invalid, wrong
// state) takes nothing: control is held from the first input that is applied.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace rrlab::server {

class Controller {
 public:
  using Notify = std::function<void(const nlohmann::json&)>;
  using Clock = std::chrono::steady_clock;
  static constexpr std::chrono::seconds kRestControlLapse{60};

  // `now`: the clock the REST lapse is measured with (tests give their own).
  explicit Controller(std::function<Clock::time_point()> now = &Clock::now, Clock::duration lapse = kRestControlLapse)
      : now_(std::move(now)), lapse_(lapse) {}

  // A WebSocket connection of `client`, told the control state now and at
  // every change through `notify` (called without the lock held, from the
  // thread that made the change); returns the handle for detach().
  std::uint64_t attach(const std::string& client, Notify notify);
  // The connection closed: control is released when it was the holder's last one.
  void detach(std::uint64_t connection);

  // An input or control from `client`: throws DomainError (conflict, "not_controller")
  // if another client holds control, else runs `act`. When nobody held
  // control, `client` holds it while `act` runs and keeps it (everyone is
  // told) only if `act` returns: a refused input takes nothing. An empty name
  // (an unnamed REST request) passes and holds nothing.
  template <typename Act>
  auto steer(const std::string& client, Act&& act) -> decltype(act()) {
    const bool fresh = hold(client);
    try {
      if constexpr (std::is_void_v<decltype(act())>) {
        act();
        if (fresh) announce();
      } else {
        auto result = act();
        if (fresh) announce();
        return result;
      }
    } catch (...) {
      if (fresh) unhold(client);
      throw;
    }
  }
  // `client` takes control (the previous holder is told); returns state_json.
  nlohmann::json take(const std::string& client);
  // `client` lets go (nothing if it does not hold control); returns state_json.
  nlohmann::json release(const std::string& client);
  // {"controller": "you" | "other" | "none"} as seen by `client`.
  nlohmann::json state_json(const std::string& client);

 private:
  // steer's parts: hold returns true when `client` holds control anew (no one
  // told yet); announce tells everyone; unhold lets go of a fresh hold.
  bool hold(const std::string& client);
  void announce();
  void unhold(const std::string& client);
  // A REST-only holder silent for longer than the lapse holds nothing; true when it lapsed now.
  bool lapse_locked();
  nlohmann::json state_locked(const std::string& client) const;
  // {"type": "control", "event": "state", "controller": ...} as seen by `client`.
  nlohmann::json state_message_locked(const std::string& client) const;
  using Notices = std::vector<std::pair<Notify, nlohmann::json>>;
  // Each connection's view of the state, to send once the lock is released.
  Notices state_notices_locked() const;
  static void send(const Notices& notices);

  struct Connection {
    std::string client;
    Notify notify;
  };
  std::function<Clock::time_point()> now_;
  Clock::duration lapse_;
  std::mutex mutex_;
  std::string holder_;  // empty: nobody
  Clock::time_point holder_seen_{};  // the holder's last input, take or claim
  std::map<std::uint64_t, Connection> connections_;
  std::uint64_t next_ = 0;
};

// A client name as accepted: 1 to 64 of [A-Za-z0-9_.-]; else empty.
std::string valid_client_name(const std::string& name);

}  // namespace rrlab::server

// What one peer may hold, so that one client cannot take what every other
// needs: TCP connections per address, and WebSockets per address, per client
// name and in all, with two reserves of WebSockets:
// - the token holders': the last sixteenth, which tokenless watchers under
//   --public-read never take, so that they cannot lock the holder out;
// - the newcomers': an eighth (--websocket-newcomer-reserve), below the
//   token holders' where the server has a token, which clients without a
//   token take only while their address holds fewer than its fair share
//   (--websocket-fair-share), so that a few greedy addresses filling their
//   caps still leave a new client its sockets.
//   Addresses are all a server without a token can tell clients apart by, and
//   many are cheap (127.0.0.0/8, an IPv6 /64): this keeps a new client in
//   against a few hogs, not against one with many addresses (docs/api.md).
//
// At its connection cap an address makes room by closing its own oldest
// connection that is only waiting for a request's header (half-sent or
// idle): a flood of stalled connections from an address does not keep that
// address's real requests (every local process shares 127.0.0.1) waiting.
// Plain types, no Beast: the rules are tested as a unit.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

namespace rrlab::server {

struct PeerCaps {
  int connections_per_address = 256;  // serve --connections-per-address
  int websockets = 1024;              // serve --max-websockets
  int websockets_per_address = 128;   // serve --websockets-per-address
  int websockets_per_client = 32;     // serve --websockets-per-client (per client name)
  int websocket_fair_share = 8;       // serve --websocket-fair-share: an address holding fewer is a newcomer
  std::optional<int> websocket_newcomer_reserve;  // serve --websocket-newcomer-reserve; unset: an eighth
  // WebSockets kept for token holders: a sixteenth of the total
  int token_reserve() const { return websockets / 16; }
  // WebSockets kept for newcomers: an eighth of the total unless set
  int newcomer_reserve() const { return websocket_newcomer_reserve.value_or(websockets / 8); }
};

// Who opens a WebSocket, as the reserves see it.
enum class Standing {
  token_holder,  // sent the server's token: may take every slot
  anonymous,     // the server has no token: anyone may steer, nobody is known
  watcher,       // no token on a --public-read server: never the token holders' reserve
};

class PeerLimits {
 public:
  explicit PeerLimits(PeerCaps caps = {}) : caps_(caps) {}

  // Held while a connection or WebSocket lives; released with its last copy.
  using Hold = std::shared_ptr<void>;

  // How the limits may close a connection to make room for a newer one.
  struct Closable {
    std::function<bool()> waiting_for_request;  // true: it may be closed (no request under way)
    std::function<void()> close;
  };

  // A connection from `address`; null when the address is at its cap and none
  // of its connections can be closed for it.
  Hold connection(const std::string& address, Closable closable);
  // A WebSocket from `address` of client `client` ("": unnamed, a client of
  // its own). Null with the reason in `refused` when over a cap or where only
  // a reserve is left that `standing` (and the address's holding) may not use.
  Hold websocket(const std::string& address, const std::string& client, Standing standing, std::string& refused);

  int connections(const std::string& address);
  int websockets();
  const PeerCaps& caps() const { return caps_; }

 private:
  struct Counts {
    int websockets = 0;
    std::map<std::uint64_t, Closable> connections;  // by id: oldest first
  };
  void release_connection(const std::string& address, std::uint64_t id);
  void release_websocket(const std::string& address, const std::string& client);

  const PeerCaps caps_;
  std::mutex mutex_;
  std::map<std::string, Counts> addresses_;
  std::map<std::string, int> clients_;  // WebSockets per client name
  int websockets_ = 0;
  std::uint64_t next_ = 0;
};

}  // namespace rrlab::server

#include <rrlab/server/net/peer_limits.hpp>

#include <vector>

namespace rrlab::server {

namespace {

// Why a WebSocket of `standing`, from an address that holds `held`, finds no
// room while `open` are open in all; "" when it finds some.
std::string no_room(const PeerCaps& caps, Standing standing, int held, int open) {
  const std::string total = "too many WebSocket clients (" + std::to_string(caps.websockets) + ")";
  if (standing == Standing::token_holder) return open < caps.websockets ? "" : total;
  const int tokenless = caps.websockets - (standing == Standing::watcher ? caps.token_reserve() : 0);
  if (open >= tokenless)
    return standing == Standing::watcher
               ? "too many watchers without a token: the remaining WebSockets are kept for clients with one"
               : total;
  if (held >= caps.websocket_fair_share && open >= tokenless - caps.newcomer_reserve())
    return "too many WebSocket clients: the last " + std::to_string(caps.newcomer_reserve()) +
           " are kept for new clients (addresses holding fewer than " + std::to_string(caps.websocket_fair_share) +
           "), and this address holds " + std::to_string(held);
  return "";
}

}  // namespace

PeerLimits::Hold PeerLimits::connection(const std::string& address, Closable closable) {
  std::function<void()> close_for_room;
  std::uint64_t id = 0;
  {
    std::lock_guard lock(mutex_);
    Counts& counts = addresses_[address];
    const int open = int(counts.connections.size());
    if (open >= caps_.connections_per_address) {
      // closed ones stay counted until their session ends: twice the cap at most
      if (open >= 2 * caps_.connections_per_address) return nullptr;
      for (auto it = counts.connections.begin(); it != counts.connections.end(); ++it) {
        if (!it->second.waiting_for_request || !it->second.waiting_for_request()) continue;
        close_for_room = it->second.close;
        it->second.waiting_for_request = nullptr;  // closed once
        break;
      }
      if (!close_for_room) return nullptr;
    }
    id = ++next_;
    counts.connections.emplace(id, std::move(closable));
  }
  if (close_for_room) close_for_room();  // unlocked: it posts onto the other connection's strand
  return Hold(static_cast<void*>(this), [this, address, id](void*) { release_connection(address, id); });
}

void PeerLimits::release_connection(const std::string& address, std::uint64_t id) {
  std::function<bool()> waiting;
  std::function<void()> close;  // destroyed unlocked: they hold weak references to sessions
  std::lock_guard lock(mutex_);
  auto it = addresses_.find(address);
  if (it == addresses_.end()) return;
  auto entry = it->second.connections.find(id);
  if (entry != it->second.connections.end()) {
    waiting = std::move(entry->second.waiting_for_request);
    close = std::move(entry->second.close);
    it->second.connections.erase(entry);
  }
  if (it->second.connections.empty() && it->second.websockets == 0) addresses_.erase(it);
}

PeerLimits::Hold PeerLimits::websocket(const std::string& address, const std::string& client, Standing standing,
                                       std::string& refused) {
  std::lock_guard lock(mutex_);
  const auto known = addresses_.find(address);
  const int held = known == addresses_.end() ? 0 : known->second.websockets;
  refused = no_room(caps_, standing, held, websockets_);
  if (!refused.empty()) return nullptr;
  if (held >= caps_.websockets_per_address) {
    refused = "too many WebSockets from this address (" + std::to_string(caps_.websockets_per_address) + ")";
    return nullptr;
  }
  if (!client.empty() && clients_[client] >= caps_.websockets_per_client) {
    refused = "too many WebSockets of client '" + client + "' (" + std::to_string(caps_.websockets_per_client) + ")";
    return nullptr;
  }
  ++websockets_;
  ++addresses_[address].websockets;
  if (!client.empty()) ++clients_[client];
  return Hold(static_cast<void*>(this), [this, address, client](void*) { release_websocket(address, client); });
}

void PeerLimits::release_websocket(const std::string& address, const std::string& client) {
  std::lock_guard lock(mutex_);
  --websockets_;
  if (auto it = addresses_.find(address); it != addresses_.end()) {
    --it->second.websockets;
    if (it->second.connections.empty() && it->second.websockets == 0) addresses_.erase(it);
  }
  if (!client.empty())
    if (auto it = clients_.find(client); it != clients_.end() && --it->second == 0) clients_.erase(it);
}

int PeerLimits::connections(const std::string& address) {
  std::lock_guard lock(mutex_);
  auto it = addresses_.find(address);
  return it == addresses_.end() ? 0 : int(it->second.connections.size());
}

int PeerLimits::websockets() {
  std::lock_guard lock(mutex_);
  return websockets_;
}

}  // namespace rrlab::server

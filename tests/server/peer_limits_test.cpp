// One peer cannot take what the others need (net/peer_limits.hpp): caps per
// address and per client name well below the total, a reserve that watchers
// without a token cannot use, a reserve for new clients that addresses past
// their fair share cannot use, and at an address's connection cap its oldest
// connection that waits for a request is closed for the new one.
#include <rrlab/server/net/peer_limits.hpp>

#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <vector>

#include "raw_connection.hpp"
#include "server_fixture.hpp"
#include "support/eventually.hpp"

namespace rrlab::testing {
namespace {

using server::PeerCaps;
using server::PeerLimits;
using server::Standing;

TEST(PeerLimitsUnit, WebSocketsPerAddressPerClientAndTheReserve) {
  // the token holders' reserve: 32 / 16 = 2
  PeerLimits limits(PeerCaps{.websockets = 32, .websockets_per_address = 12, .websockets_per_client = 4});
  std::vector<PeerLimits::Hold> held;
  std::string why;
  for (int i = 0; i < 4; ++i) held.push_back(limits.websocket("10.0.0.1", "tab", Standing::token_holder, why));
  EXPECT_FALSE(limits.websocket("10.0.0.1", "tab", Standing::token_holder, why));
  EXPECT_NE(why.find("client 'tab'"), std::string::npos) << why;
  for (int i = 0; i < 8; ++i)
    held.push_back(limits.websocket("10.0.0.1", "", Standing::token_holder, why));  // unnamed: its own client
  EXPECT_FALSE(limits.websocket("10.0.0.1", "", Standing::token_holder, why));
  EXPECT_NE(why.find("this address"), std::string::npos) << why;
  // other addresses fill the rest, watchers without a token up to the reserve
  for (int i = 0; i < 18; ++i)
    held.push_back(limits.websocket("10.0.1." + std::to_string(i), "", Standing::watcher, why));
  EXPECT_EQ(limits.websockets(), 30);
  EXPECT_FALSE(limits.websocket("10.0.2.1", "", Standing::watcher, why));
  EXPECT_NE(why.find("kept for clients with one"), std::string::npos) << why;
  held.push_back(limits.websocket("10.0.2.1", "", Standing::token_holder, why));  // the token holder still gets in
  EXPECT_TRUE(held.back());
  held.push_back(limits.websocket("10.0.2.2", "", Standing::token_holder, why));
  EXPECT_FALSE(limits.websocket("10.0.2.3", "", Standing::token_holder, why));  // the total
  for (auto& h : held) ASSERT_TRUE(h);
  held.clear();
  EXPECT_EQ(limits.websockets(), 0);
  EXPECT_TRUE(limits.websocket("10.0.0.1", "tab", Standing::token_holder, why));
}

TEST(PeerLimitsUnit, PastTheirFairShareAddressesLeaveTheNewcomerReserve) {
  PeerLimits limits(PeerCaps{
      .websockets = 32, .websockets_per_address = 16, .websocket_fair_share = 2, .websocket_newcomer_reserve = 8});
  std::vector<PeerLimits::Hold> held;
  std::string why;
  const auto take = [&](const std::string& address, Standing standing = Standing::anonymous) {
    PeerLimits::Hold hold = limits.websocket(address, "", standing, why);
    if (hold) held.push_back(hold);
    return bool(hold);
  };
  for (int i = 0; i < 16; ++i) ASSERT_TRUE(take("10.0.0.2"));
  for (int i = 0; i < 8; ++i) ASSERT_TRUE(take("10.0.0.3"));
  // 24 = 32 - 8: an address that holds its share or more gets no more, below its own cap
  EXPECT_FALSE(take("10.0.0.3"));
  EXPECT_NE(why.find("kept for new clients"), std::string::npos) << why;
  // a new address gets its share, then no more
  EXPECT_TRUE(take("10.0.0.4"));
  EXPECT_TRUE(take("10.0.0.4"));
  EXPECT_FALSE(take("10.0.0.4"));
  // ... until enough new addresses take the whole reserve: what addresses alone can promise
  for (const std::string address : {"10.0.0.5", "10.0.0.6", "10.0.0.7"})
    for (int i = 0; i < 2; ++i) EXPECT_TRUE(take(address)) << address;
  EXPECT_FALSE(take("10.0.0.8"));
  EXPECT_NE(why.find("(32)"), std::string::npos) << why;
  // a greedy address's sockets closed: room for the others again
  held.erase(held.begin(), held.begin() + 16);
  EXPECT_TRUE(take("10.0.0.3"));

  // under --public-read, watchers stop 2 (a sixteenth) earlier, and a token holder is not a newcomer but has it all
  PeerLimits public_read(PeerCaps{
      .websockets = 32, .websockets_per_address = 32, .websocket_fair_share = 2, .websocket_newcomer_reserve = 8});
  std::vector<PeerLimits::Hold> watching;  // released before public_read goes
  for (int i = 0; i < 22; ++i) watching.push_back(public_read.websocket("10.0.1.1", "", Standing::watcher, why));
  EXPECT_FALSE(public_read.websocket("10.0.1.1", "", Standing::watcher, why));
  EXPECT_NE(why.find("kept for new clients"), std::string::npos) << why;
  for (int i = 0; i < 8; ++i)
    watching.push_back(public_read.websocket("10.0.1." + std::to_string(2 + i / 2), "", Standing::watcher, why));
  EXPECT_FALSE(public_read.websocket("10.0.1.9", "", Standing::watcher, why));
  EXPECT_NE(why.find("kept for clients with one"), std::string::npos) << why;
  EXPECT_TRUE(public_read.websocket("10.0.1.1", "", Standing::token_holder, why));
  for (auto& h : watching) EXPECT_TRUE(h);
}

TEST(PeerLimitsUnit, AtTheConnectionCapTheOldestWaitingConnectionMakesRoom) {
  PeerLimits limits(PeerCaps{.connections_per_address = 4});
  std::vector<int> closed;
  std::vector<bool> waiting = {false, true, true, false};
  std::vector<PeerLimits::Hold> held;
  for (int i = 0; i < 4; ++i)
    held.push_back(limits.connection("127.0.0.1", {[&waiting, i] { return bool(waiting[size_t(i)]); },
                                                   [&closed, i] { closed.push_back(i); }}));
  // the fifth closes the oldest that waits for a request (1), not the busy 0
  held.push_back(limits.connection("127.0.0.1", {[] { return false; }, [] {}}));
  ASSERT_TRUE(held.back());
  EXPECT_EQ(closed, std::vector<int>{1});
  held.push_back(limits.connection("127.0.0.1", {[] { return false; }, [] {}}));
  EXPECT_EQ(closed, (std::vector<int>{1, 2}));
  // nothing waits: refused; another address is not concerned
  EXPECT_FALSE(limits.connection("127.0.0.1", {[] { return true; }, [] {}}));
  EXPECT_TRUE(limits.connection("127.0.0.2", {[] { return true; }, [] {}}));
  held.erase(held.begin() + 1);  // 1's session ended
  EXPECT_EQ(limits.connections("127.0.0.1"), 5);
}

// Over the network: a process holding a client's WebSocket share and an
// address's stalled connections does not keep /api/health or another
// client's WebSocket out.
TEST(PeerLimitsServer, HalfSentRequestsAndSocketFloodsLeaveRoomForOthers) {
  ServerProcess server("", {"--connections-per-address", "16", "--websockets-per-client", "3"});
  const HttpResult run = http_json(server.port(), "POST", "/api/runs",
                                   {{"scenario", small_scenario("joystick", 600)}, {"paused", true}});
  ASSERT_EQ(run.status, 201) << run.body;
  const std::string ws = "/ws/runs/" + std::to_string(run.json()["id"].get<long>());
  std::vector<std::unique_ptr<WsClient>> mallory;
  for (int i = 0; i < 3; ++i) mallory.push_back(std::make_unique<WsClient>(server.port(), ws + "?client=mallory"));
  EXPECT_EQ(ws_upgrade(server.port(), ws + "?client=mallory").status, 503);
  WsClient alice(server.port(), ws + "?client=alice");
  EXPECT_TRUE(alice.read_type("snapshot"));
  // 40 connections that never finish their header, from the same address as everyone here
  std::vector<std::unique_ptr<RawConnection>> stalled;
  for (int i = 0; i < 40; ++i) {
    stalled.push_back(std::make_unique<RawConnection>(server.port()));
    stalled.back()->write("GET /api/health HTTP/1.1\r\nHost: 127.0.0.1\r\n");
  }
  for (int i = 0; i < 5; ++i) EXPECT_EQ(http(server.port(), "GET", "/api/health").status, 200) << i;
  // alice's socket still steers
  alice.send(R"({"type": "input", "kind": "joystick", "payload": {"linear": [0.1, 0]}})");
  EXPECT_TRUE(alice.read_type("ack"));
}

// A WebSocket of `target` opened with raw bytes from the loopback address
// `from`: the connection when the server answered 101, else null with the
// server's answer in `refusal`.
std::unique_ptr<RawConnection> open_websocket(unsigned short port, const std::string& target, const std::string& from,
                                              std::string& refusal) {
  auto connection = std::make_unique<RawConnection>(port, 0, from);
  connection->write(websocket_upgrade_request(port, target));
  if (status_of(connection->read_until("\r\n\r\n")) == 101) return connection;
  refusal = connection->read_until("}}");
  return nullptr;
}

// The attack of the issue, scaled down: without a token, nine loopback
// addresses each try to take an eighth of the slots. The ones past their fair
// share are refused before the newcomer reserve, so a new address (and the
// common 127.0.0.1) still gets sockets; a greedy one does again once others close.
TEST(PeerLimitsServer, GreedyAddressesLeaveNewcomersTheirSockets) {
  ServerProcess server("", {"--max-websockets", "64", "--websockets-per-address", "8", "--websocket-newcomer-reserve",
                            "8", "--websocket-fair-share", "2"});
  const HttpResult run =
      http_json(server.port(), "POST", "/api/runs", {{"scenario", small_scenario("joystick", 600)}, {"paused", true}});
  ASSERT_EQ(run.status, 201) << run.body;
  const std::string ws = "/ws/runs/" + std::to_string(run.json()["id"].get<long>());
  std::map<std::string, std::vector<std::unique_ptr<RawConnection>>> open;  // by address
  std::map<std::string, std::string> refused;                               // each address's first refusal
  for (int last = 2; last <= 10; ++last) {
    const std::string address = "127.0.0." + std::to_string(last);
    for (int i = 0; i < 8; ++i) {
      auto socket = open_websocket(server.port(), ws, address, refused[address]);
      if (!socket) break;
      open[address].push_back(std::move(socket));
    }
  }
  // seven took their 8 (56 = 64 - 8); the two later ones only their share of the reserve
  for (int last = 2; last <= 8; ++last) EXPECT_EQ(open["127.0.0." + std::to_string(last)].size(), 8u) << last;
  for (const std::string address : {"127.0.0.9", "127.0.0.10"}) {
    EXPECT_EQ(open[address].size(), 2u) << address;
    EXPECT_EQ(status_of(refused[address]), 503) << refused[address];
    EXPECT_NE(refused[address].find("kept for new clients"), std::string::npos) << refused[address];
  }
  // a new address is served, up to its share
  std::string why;
  for (int i = 0; i < 2; ++i) {
    open["127.0.0.11"].push_back(open_websocket(server.port(), ws, "127.0.0.11", why));
    EXPECT_TRUE(open["127.0.0.11"].back()) << why;
  }
  EXPECT_FALSE(open_websocket(server.port(), ws, "127.0.0.11", why));
  WsClient local(server.port(), ws);  // from 127.0.0.1
  EXPECT_TRUE(local.read_type("snapshot"));
  // one greedy address closes its sockets: another one past its share gets more again
  open["127.0.0.2"].clear();
  rrlab::test::eventually(
      [&] {
        auto socket = open_websocket(server.port(), ws, "127.0.0.9", why);
        if (socket) open["127.0.0.9"].push_back(std::move(socket));
        return open["127.0.0.9"].size() > 2;
      },
      std::chrono::seconds(30), "a socket for 127.0.0.9 once 127.0.0.2 closed its eight");
}

}  // namespace
}  // namespace rrlab::testing

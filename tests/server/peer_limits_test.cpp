// One peer cannot take what the others need (net/peer_limits.hpp): caps per
// address and per client name well below the total, a reserve that watchers
// without a token cannot use, and at an address's connection cap its oldest
// connection that waits for a request is closed for the new one.
#include "net/peer_limits.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "raw_connection.hpp"
#include "server_fixture.hpp"

namespace rrlab::testing {
namespace {

using server::PeerCaps;
using server::PeerLimits;

TEST(PeerLimitsUnit, WebSocketsPerAddressPerClientAndTheReserve) {
  PeerLimits limits(PeerCaps{256, 32, 12, 4});  // reserve: 32 / 16 = 2
  std::vector<PeerLimits::Hold> held;
  std::string why;
  for (int i = 0; i < 4; ++i) held.push_back(limits.websocket("10.0.0.1", "tab", true, why));
  EXPECT_FALSE(limits.websocket("10.0.0.1", "tab", true, why));
  EXPECT_NE(why.find("client 'tab'"), std::string::npos) << why;
  for (int i = 0; i < 8; ++i) held.push_back(limits.websocket("10.0.0.1", "", true, why));  // unnamed: its own client
  EXPECT_FALSE(limits.websocket("10.0.0.1", "", true, why));
  EXPECT_NE(why.find("this address"), std::string::npos) << why;
  // other addresses fill the rest, watchers without a token up to the reserve
  for (int i = 0; i < 18; ++i) held.push_back(limits.websocket("10.0.1." + std::to_string(i), "", false, why));
  EXPECT_EQ(limits.websockets(), 30);
  EXPECT_FALSE(limits.websocket("10.0.2.1", "", false, why));
  EXPECT_NE(why.find("kept for clients with one"), std::string::npos) << why;
  held.push_back(limits.websocket("10.0.2.1", "", true, why));  // the token holder still gets in
  EXPECT_TRUE(held.back());
  held.push_back(limits.websocket("10.0.2.2", "", true, why));
  EXPECT_FALSE(limits.websocket("10.0.2.3", "", true, why));  // the total
  for (auto& h : held) ASSERT_TRUE(h);
  held.clear();
  EXPECT_EQ(limits.websockets(), 0);
  EXPECT_TRUE(limits.websocket("10.0.0.1", "tab", true, why));
}

TEST(PeerLimitsUnit, AtTheConnectionCapTheOldestWaitingConnectionMakesRoom) {
  PeerLimits limits(PeerCaps{4, 1024, 128, 32});
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

}  // namespace
}  // namespace rrlab::testing

// A live run over REST and WebSocket: snapshot first, then frames; inputs
// show in later frames, in the run's parameters and in its events.
#include "server_fixture.hpp"

#include <rrlab/server/routes/routes.hpp>

namespace rrlab::testing {
namespace {

using nlohmann::json;

class LiveRun : public ServerTest {};

TEST_F(LiveRun, SnapshotThenFramesAndInputsTakeEffect) {
  json scenario = small_scenario("joystick", 600);
  const std::int64_t id = start_live({{"scenario", scenario}, {"rate", 1}});
  const std::string base = "/api/runs/" + std::to_string(id);
  WsClient ws(port(), "/ws/runs/" + std::to_string(id));
  const auto snapshot = ws.read_json();
  ASSERT_TRUE(snapshot);
  EXPECT_EQ((*snapshot)["type"], "snapshot");
  EXPECT_EQ((*snapshot)["model"]["dof"], 4);
  EXPECT_EQ((*snapshot)["obstacles"][0]["id"], "ball");
  EXPECT_TRUE((*snapshot)["params"].contains("gain"));

  auto frame = ws.read_type("frame");
  ASSERT_TRUE(frame);
  EXPECT_EQ((*frame)["links"].size(), 4u);
  EXPECT_EQ((*frame)["q"].size(), 4u);
  const double distance_before = (*frame)["metrics"]["min_distance"];

  // moving the obstacle next to the arm shrinks the distance in later frames
  const json links = (*frame)["links"];
  const double ex = links[3][3], ey = links[3][4];  // the tip
  ASSERT_EQ(send("PUT", base + "/obstacles/ball", {{"position", {ex + 0.15, ey}}}).status, 200);
  double distance_after = distance_before;
  for (int i = 0; i < 60 && distance_after >= distance_before - 1e-6; ++i) {
    auto next = ws.read_type("frame");
    ASSERT_TRUE(next);
    if ((*next)["metrics"]["min_distance"].is_number()) distance_after = (*next)["metrics"]["min_distance"];
  }
  EXPECT_LT(distance_after, 0.1);

  // a parameter change: in the run's params, in its events (stored before the
  // answer), and a params message on the socket (not a new snapshot)
  ASSERT_EQ(send("PATCH", base + "/params", {{"gain", 4.25}}).status, 200);
  EXPECT_EQ(get(base).json()["live"]["params"]["gain"], 4.25);
  const json events = get(base + "/events").json();
  ASSERT_GE(events.size(), 2u);
  EXPECT_EQ(events.back()["kind"], "params");
  EXPECT_EQ(events.back()["payload"]["gain"], 4.25);
  auto changed = ws.read_type("params");
  ASSERT_TRUE(changed);
  EXPECT_EQ((*changed)["params"]["gain"], 4.25);

  // joystick: the target moves along +x
  auto before = ws.read_type("frame");
  ASSERT_TRUE(before);
  const double x0 = (*before)["target"][0];
  ASSERT_EQ(send("POST", base + "/joystick", {{"linear", {0.3, 0}}}).status, 200);
  // held until the frames show the target 3 cm along +x (0.1 s at 0.3 m/s), however long that takes
  std::optional<json> after;
  for (int i = 0; i < 3000; ++i) {
    after = ws.read_type("frame");
    ASSERT_TRUE(after) << "no frame while the joystick is held";
    if ((*after)["target"][0].get<double>() > x0 + 0.03) break;
  }
  ASSERT_EQ(send("POST", base + "/joystick", {{"linear", {0, 0}}}).status, 200);
  EXPECT_GT((*after)["target"][0].get<double>(), x0 + 0.03)
      << "before seq " << (*before)["seq"] << ", after seq " << (*after)["seq"];

  // inputs over the socket are validated like REST
  ws.send(R"({"type":"input","kind":"params","payload":{"gain":-5}})");
  auto error = ws.read_type("error");
  ASSERT_TRUE(error);
  EXPECT_EQ((*error)["error"]["path"], "payload.gain");
  ws.send(R"({"type":"input","kind":"params","payload":{"gain":2}})");
  ASSERT_TRUE(ws.read_type("ack"));
  ws.send("not json");
  auto malformed = ws.read_type("error");
  ASSERT_TRUE(malformed);
  EXPECT_EQ((*malformed)["error"]["code"], "malformed_json");

  EXPECT_EQ(send("POST", base + "/control", {{"action", "stop"}}).status, 200);
  EXPECT_EQ(wait_ended(id)["status"], "stopped");
}

// What changed goes to clients as what it is: an obstacle moved is a scene
// message, a parameter change a params message, and only a change of what
// the snapshot describes (a method switch, an obstacle added) a new snapshot.
TEST_F(LiveRun, ClientsGetWhatChangedNotANewSnapshot) {
  const std::int64_t id = start_live({{"scenario", small_scenario()}, {"paused", true}});
  const std::string base = "/api/runs/" + std::to_string(id);
  WsClient ws(port(), "/ws/runs/" + std::to_string(id));
  ASSERT_TRUE(ws.read_type("snapshot"));
  // the next message that is not a frame
  const auto next_change = [&] {
    for (int i = 0; i < 200; ++i) {
      auto m = ws.read_json();
      if (!m) break;
      if ((*m)["type"] != "frame" && (*m)["type"] != "control") return *m;
    }
    return json();
  };
  ASSERT_EQ(send("PUT", base + "/obstacles/ball", {{"position", {0.3, 1.1}}}).status, 200);
  json m = next_change();
  ASSERT_EQ(m["type"], "scene") << m.dump();
  EXPECT_EQ(m["obstacles"][0]["id"], "ball");
  EXPECT_EQ(m["obstacles"][0]["center"][0], 0.3);
  const std::uint64_t after_move = m["scene_version"];

  ASSERT_EQ(send("PATCH", base + "/params", {{"gain", 3}}).status, 200);
  m = next_change();
  ASSERT_EQ(m["type"], "params") << m.dump();
  EXPECT_EQ(m["params"]["gain"], 3);
  EXPECT_GT(m["scene_version"].get<std::uint64_t>(), after_move);

  ASSERT_EQ(send("POST", base + "/obstacles", {{"id", "dot"}, {"shape", "point"}, {"position", {1.0, 1.0}}}).status,
            200);
  m = next_change();
  ASSERT_EQ(m["type"], "snapshot") << m.dump();
  EXPECT_EQ(m["obstacles"].size(), 2u);

  ASSERT_EQ(send("POST", base + "/method", {{"name", "dls"}}).status, 200);
  m = next_change();
  ASSERT_EQ(m["type"], "snapshot") << m.dump();
  EXPECT_EQ(m["method"], "dls");
  EXPECT_EQ(send("POST", base + "/control", {{"action", "stop"}}).status, 200);
}

TEST_F(LiveRun, UnknownRunsHaveNoSocket) {
  EXPECT_THROW(WsClient(port(), "/ws/runs/987654"), std::runtime_error);
  EXPECT_THROW(WsClient(port(), "/ws/runs/x"), std::runtime_error);
  EXPECT_THROW(WsClient(port(), "/ws/replays/987654"), std::runtime_error);
  EXPECT_THROW(WsClient(port(), "/ws/runs/1/more"), std::runtime_error);
  EXPECT_THROW(WsClient(port(), "/ws/elsewhere/1"), std::runtime_error);
}

// The router's table holds the WebSocket routes next to the REST ones.
TEST(RouteTable, HoldsTheWebSocketRoutes) {
  std::vector<std::string> patterns;
  for (const server::RouteInfo& route : server::websocket_routes()) {
    EXPECT_EQ(route.verb, "GET");
    patterns.push_back(route.pattern);
  }
  EXPECT_EQ(patterns, (std::vector<std::string>{"/ws/runs/{}", "/ws/replays/{}"}));
}

}  // namespace
}  // namespace rrlab::testing

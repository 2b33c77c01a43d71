// A live run over REST and WebSocket: snapshot first, then frames; inputs
// show in later frames, in the run's parameters and in its events.
#include "server_fixture.hpp"

#include "routes/routes.hpp"

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

  // a parameter change: in the run's params, in its events, and a new snapshot on the socket
  ASSERT_EQ(send("PATCH", base + "/params", {{"gain", 4.25}}).status, 200);
  EXPECT_EQ(get(base).json()["live"]["params"]["gain"], 4.25);
  const json events = get(base + "/events").json();
  ASSERT_GE(events.size(), 2u);
  EXPECT_EQ(events.back()["kind"], "params");
  EXPECT_EQ(events.back()["payload"]["gain"], 4.25);
  auto resnap = ws.read_type("snapshot");
  ASSERT_TRUE(resnap);
  EXPECT_EQ((*resnap)["params"]["gain"], 4.25);

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

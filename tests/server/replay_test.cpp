// Stored frames played back over the WebSocket at a chosen speed, with pause
// and seek; inputs to batch runs are refused.
#include <algorithm>
#include <cmath>

#include "server_fixture.hpp"

namespace rrlab::testing {
namespace {

using nlohmann::json;

class Replay : public ServerTest {};

// A stored (exact) value against the streamed one: numbers to 7 significant
// digits (0.99999999 streams as 1), arrays element by element, objects by the
// stored keys (the stream adds step_us to the metrics).
void expect_same_to_7_digits(const json& exact, const json& drawn, const std::string& path) {
  if (exact.is_number() && drawn.is_number()) {
    EXPECT_NEAR(drawn.get<double>(), exact.get<double>(), 1e-6 * std::max(1.0, std::abs(exact.get<double>()))) << path;
    return;
  }
  ASSERT_EQ(exact.type(), drawn.type()) << path << ": " << exact.dump() << " vs " << drawn.dump();
  if (exact.is_object()) {
    for (const auto& [key, value] : exact.items()) {
      ASSERT_TRUE(drawn.contains(key)) << path << "." << key;
      expect_same_to_7_digits(value, drawn[key], path + "." + key);
    }
  } else if (exact.is_array()) {
    ASSERT_EQ(exact.size(), drawn.size()) << path;
    for (size_t i = 0; i < exact.size(); ++i) expect_same_to_7_digits(exact[i], drawn[i], path + "." + std::to_string(i));
  } else {
    EXPECT_EQ(exact, drawn) << path;
  }
}

TEST_F(Replay, StreamsStoredFramesWithSeek) {
  const HttpResult batch = send("POST", "/api/runs", {{"scenario", "01_planar7_obstacles"}, {"mode", "batch"}, {"steps", 400}});
  ASSERT_EQ(batch.status, 200);
  const std::int64_t id = batch.json()["id"];
  const json stored = get("/api/runs/" + std::to_string(id) + "/frames?from=100&to=100").json()["frames"][0];

  const HttpResult started = send("POST", "/api/runs/" + std::to_string(id) + "/replay", {{"mode", "frames"}, {"speed", 0.25}});  // 16 s
  ASSERT_EQ(started.status, 201) << started.body;
  const std::string rid = std::to_string(started.json()["replay"].get<long>());
  EXPECT_EQ(started.json()["frames"], 400);
  WsClient ws(port(), started.json()["ws"].get<std::string>());
  const auto snapshot = ws.read_type("snapshot");
  ASSERT_TRUE(snapshot);
  EXPECT_EQ((*snapshot)["frames"], 400);
  EXPECT_EQ((*snapshot)["model"]["dof"], 7);
  std::int64_t last = -1;
  for (int i = 0; i < 10; ++i) {
    auto frame = ws.read_type("frame");
    ASSERT_TRUE(frame);
    EXPECT_GT((*frame)["seq"].get<std::int64_t>(), last);
    last = (*frame)["seq"];
    EXPECT_EQ((*frame)["links"].size(), 7u);
  }

  // pause, seek to frame 100: the frame shown is the stored one
  HttpResult r = send("POST", "/api/replays/" + rid + "/control", {{"action", "pause"}});
  EXPECT_EQ(r.json()["playing"], false);
  r = send("POST", "/api/replays/" + rid + "/control", {{"action", "seek"}, {"seq", 100}});
  ASSERT_EQ(r.status, 200);
  EXPECT_EQ(r.json()["seq"], 100);
  std::optional<json> frame;
  for (int i = 0; i < 200; ++i) {
    frame = ws.read_type("frame");
    ASSERT_TRUE(frame);
    if ((*frame)["seq"] == 100) break;
  }
  EXPECT_EQ((*frame)["seq"], 100);
  // one frame shape: every stored field is in the streamed frame, which
  // carries 7 significant digits of the stored exact value
  ASSERT_TRUE(stored["metrics"].is_object());
  ASSERT_TRUE(stored["diagnostics"].is_array());
  expect_same_to_7_digits(stored, *frame, "frame");

  EXPECT_EQ(error_of(send("POST", "/api/replays/" + rid + "/control", {{"action", "seek"}, {"seq", 400}}))["path"], "seq");
  EXPECT_EQ(error_of(send("POST", "/api/replays/" + rid + "/control", {{"speed", 0}}))["path"], "speed");
  EXPECT_EQ(get("/api/replays/9999").status, 404);
  EXPECT_EQ(error_of(send("POST", "/api/runs/" + std::to_string(id) + "/replay", {{"mode", "rewind"}}))["path"], "mode");
  EXPECT_EQ(error_of(send("POST", "/api/runs/" + std::to_string(id) + "/replay", {{"from", 1000}}))["path"], "from");
}

TEST_F(Replay, BatchRunsTakeNoInputs) {
  json scenario = small_scenario("joystick", 8000);  // 800,000 frames: within --max-run-bytes
  const HttpResult started = send("POST", "/api/runs", {{"scenario", scenario}, {"mode", "batch"}, {"wait", false}});
  ASSERT_EQ(started.status, 201);
  const std::string base = "/api/runs/" + std::to_string(started.json()["id"].get<long>());
  const HttpResult joystick = send("POST", base + "/joystick", {{"linear", {0.1, 0}}});
  EXPECT_EQ(joystick.status, 409);
  EXPECT_EQ(error_of(joystick)["code"], "wrong_state");
  EXPECT_EQ(send("POST", base + "/control", {{"action", "pause"}}).status, 409);
  EXPECT_EQ(send("POST", base + "/control", {{"action", "stop"}}).status, 200);
  EXPECT_EQ(wait_ended(started.json()["id"])["status"], "stopped");
}

// One client making replays fast cannot end another's: before, 32 replays
// made in 0.03 s evicted a watched, playing replay (its stream froze and its
// controls answered 404). Now a client has 8; past that its own oldest
// unwatched replay ends, and one that is watched or new is never ended.
TEST_F(Replay, OneClientCannotEvictAnothersWatchedReplay) {
  const HttpResult batch = send("POST", "/api/runs", {{"scenario", "01_planar7_obstacles"}, {"mode", "batch"}, {"steps", 300}});
  ASSERT_EQ(batch.status, 200);
  const std::string replay_of = "/api/runs/" + std::to_string(batch.json()["id"].get<long>()) + "/replay";
  const HttpResult watched = http(port(), "POST", replay_of, R"({"speed": 0.05})", "", {{"Rrlab-Client", "bob"}});
  ASSERT_EQ(watched.status, 201) << watched.body;
  const std::string control = "/api/replays/" + std::to_string(watched.json()["replay"].get<long>()) + "/control";
  WsClient bob(port(), watched.json()["ws"].get<std::string>());
  ASSERT_TRUE(bob.read_type("snapshot"));

  int made = 0, refused = 0;
  for (int i = 0; i < 40; ++i) {  // no client name: the address is the client
    const HttpResult r = send("POST", replay_of, {{"speed", 0.05}});
    if (r.status == 201) ++made;
    if (r.status == 429) {
      ++refused;
      EXPECT_EQ(error_of(r)["code"], "too_many_replays");
    }
  }
  // 8 at once; more only where a slow machine let an unconnected one pass its 10 s
  EXPECT_GE(made, 8);
  EXPECT_EQ(made + refused, 40);
  // bob's replay lives: its controls answer and its stream goes on
  EXPECT_EQ(send("POST", control, {{"action", "seek"}, {"seq", 10}}).status, 200);
  bool seen = false;
  for (int i = 0; i < 100 && !seen; ++i) {
    const auto frame = bob.read_type("frame");
    ASSERT_TRUE(frame) << "bob's stream froze";
    seen = (*frame)["seq"] == 10;
  }
  EXPECT_TRUE(seen);
}

}  // namespace
}  // namespace rrlab::testing

// GET /api/runs/{id}/drawn (server/app/drawn_frames.cpp): stored frames as
// the replay player sends them, for the dashboard's local scrubbing; the
// scene (obstacles, method) wherever the recorded inputs changed it; pages of
// at most 2,000 frames at any stride; bad queries named.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "server_fixture.hpp"

namespace rrlab::testing {
namespace {

using nlohmann::json;

class DrawnFrames : public ServerTest {
 protected:
  // The answer's lines, parsed.
  static std::vector<json> lines_of(const HttpResult& r) {
    std::vector<json> out;
    std::istringstream in(r.body);
    for (std::string line; std::getline(in, line);)
      if (!line.empty()) out.push_back(json::parse(line));
    return out;
  }
  static std::vector<json> of_type(const std::vector<json>& lines, const std::string& type) {
    std::vector<json> out;
    for (const json& l : lines)
      if (l["type"] == type) out.push_back(l);
    return out;
  }
};

TEST_F(DrawnFrames, EachFrameIsWhatTheReplayPlayerSendsForIt) {
  const HttpResult batch = send("POST", "/api/runs", {{"scenario", "01_planar7_obstacles"}, {"mode", "batch"}, {"steps", 400}});
  ASSERT_EQ(batch.status, 200) << batch.body;
  const std::string id = std::to_string(batch.json()["id"].get<long>());
  const HttpResult r = get("/api/runs/" + id + "/drawn");
  ASSERT_EQ(r.status, 200) << r.body.substr(0, 300);
  EXPECT_EQ(r.content_type, "application/x-ndjson");
  const std::vector<json> lines = lines_of(r);
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines[0], json({{"type", "drawn"}, {"run", std::stol(id)}, {"from", 0}, {"to", 399}, {"stride", 1}, {"frames", 400}}));
  const std::vector<json> frames = of_type(lines, "frame"), scenes = of_type(lines, "scene");
  ASSERT_EQ(frames.size(), 400u);
  ASSERT_EQ(scenes.size(), 1u);  // no input: the scenario's scene throughout
  EXPECT_EQ(lines[1]["type"], "scene");
  EXPECT_EQ(scenes[0]["seq"], 0);
  EXPECT_EQ(scenes[0]["method"], "closest_point");
  EXPECT_EQ(scenes[0]["obstacles"].size(), 3u);
  for (std::size_t i = 0; i < frames.size(); ++i) EXPECT_EQ(frames[i]["seq"], i);

  // the replay player's frame 100, paused: the same message
  const HttpResult started = send("POST", "/api/runs/" + id + "/replay", {{"mode", "frames"}, {"speed", 0.25}});
  ASSERT_EQ(started.status, 201) << started.body;
  WsClient ws(port(), started.json()["ws"].get<std::string>());
  ASSERT_TRUE(ws.read_type("snapshot"));
  const std::string rid = std::to_string(started.json()["replay"].get<long>());
  ASSERT_EQ(send("POST", "/api/replays/" + rid + "/control", {{"action", "pause"}, {"seq", 100}}).status, 200);
  std::optional<json> played;
  for (int i = 0; i < 400 && !(played && (*played)["seq"] == 100 && (*played)["status"] == "paused"); ++i)
    played = ws.read_type("frame");
  ASSERT_TRUE(played);
  json drawn = frames[100];
  EXPECT_EQ(drawn["status"], "paused");
  // scene versions count different things: the player's every change, the answer's scene lines
  played->erase("scene_version");
  drawn.erase("scene_version");
  EXPECT_EQ(drawn, *played);
}

TEST_F(DrawnFrames, TheSceneComesWhereTheRecordedInputsChangedIt) {
  const std::int64_t id = start_live({{"scenario", "01_planar7_obstacles"}, {"rate", 1}, {"paused", true}});
  const std::string base = "/api/runs/" + std::to_string(id);
  const auto step = [&](int n) {
    for (int i = 0; i < n; ++i) ASSERT_EQ(send("POST", base + "/control", {{"action", "step"}}).status, 200);
  };
  step(3);
  ASSERT_EQ(send("PUT", base + "/obstacles/disc", {{"position", {0.2, 1.6}}}).status, 200);
  step(3);
  ASSERT_EQ(send("POST", base + "/method", {{"name", "dls"}}).status, 200);
  step(3);
  ASSERT_EQ(send("POST", base + "/control", {{"action", "stop"}}).status, 200);
  wait_ended(id);
  const json events = get(base + "/events").json();
  std::int64_t moved = -1, switched = -1;
  for (const json& e : events) {
    if (e["kind"] == "obstacle") moved = e["seq"];
    if (e["kind"] == "method") switched = e["seq"];
  }
  ASSERT_GE(moved, 0);
  ASSERT_GT(switched, moved);

  const std::vector<json> scenes = of_type(lines_of(get(base + "/drawn")), "scene");
  ASSERT_EQ(scenes.size(), 3u) << json(scenes);
  EXPECT_EQ(scenes[1]["seq"], moved);
  EXPECT_EQ(scenes[2]["seq"], switched);
  const auto disc = [](const json& scene) {
    for (const json& o : scene["obstacles"])
      if (o["id"] == "disc") return o["center"];
    return json();
  };
  EXPECT_NEAR(disc(scenes[0])[0].get<double>(), 0.3, 1e-12);
  EXPECT_NEAR(disc(scenes[1])[0].get<double>(), 0.2, 1e-12);
  EXPECT_NEAR(disc(scenes[1])[1].get<double>(), 1.6, 1e-12);
  EXPECT_EQ(scenes[1]["method"], "closest_point");
  EXPECT_EQ(scenes[2]["method"], "dls");

  // a page from a later frame starts with the scene as it stood there
  const std::vector<json> later = lines_of(get(base + "/drawn?from=" + std::to_string(switched)));
  ASSERT_GE(later.size(), 3u);
  EXPECT_EQ(later[1]["type"], "scene");
  EXPECT_EQ(later[1]["method"], "dls");
  EXPECT_NEAR(disc(later[1])[0].get<double>(), 0.2, 1e-12);
}

TEST_F(DrawnFrames, PagesHoldAtMostTwoThousandFramesAtAnyStride) {
  const HttpResult batch = send("POST", "/api/runs", {{"scenario", "01_planar7_obstacles"}, {"mode", "batch"}, {"steps", 2500}});
  ASSERT_EQ(batch.status, 200) << batch.body;
  const std::string base = "/api/runs/" + std::to_string(batch.json()["id"].get<long>());
  std::vector<json> lines = lines_of(get(base + "/drawn"));
  EXPECT_EQ(lines[0]["to"], 1999);
  EXPECT_EQ(of_type(lines, "frame").size(), 2000u);
  lines = lines_of(get(base + "/drawn?from=1&stride=1000"));
  const std::vector<json> strided = of_type(lines, "frame");
  ASSERT_EQ(strided.size(), 3u);
  EXPECT_EQ(strided[2]["seq"], 2001);
  lines = lines_of(get(base + "/drawn?from=2499"));
  ASSERT_EQ(of_type(lines, "frame").size(), 1u);
  EXPECT_EQ(of_type(lines, "frame")[0]["seq"], 2499);
}

TEST_F(DrawnFrames, BadQueriesAndUnknownRunsAreNamed) {
  const HttpResult batch = send("POST", "/api/runs", {{"scenario", "01_planar7_obstacles"}, {"mode", "batch"}, {"steps", 50}});
  ASSERT_EQ(batch.status, 200) << batch.body;
  const std::string base = "/api/runs/" + std::to_string(batch.json()["id"].get<long>());
  for (const auto& [query, field] : std::vector<std::pair<std::string, std::string>>{
           {"from=50", "from"}, {"from=-1", "from"}, {"from=x", "from"}, {"stride=0", "stride"},
           {"from=10&to=5", "to"}, {"to=abc", "to"}}) {
    const HttpResult r = get(base + "/drawn?" + query);
    EXPECT_EQ(r.status, 400) << query;
    EXPECT_EQ(error_of(r)["path"], field) << query << ": " << r.body;
  }
  // a live run stopped before its first step stored no frame
  const std::int64_t empty = start_live({{"scenario", "01_planar7_obstacles"}, {"paused", true}});
  ASSERT_EQ(send("POST", "/api/runs/" + std::to_string(empty) + "/control", {{"action", "stop"}}).status, 200);
  ASSERT_EQ(wait_ended(empty)["frames"], 0);
  const HttpResult none = get("/api/runs/" + std::to_string(empty) + "/drawn");
  EXPECT_EQ(none.status, 409) << none.body;
  EXPECT_EQ(error_of(none)["code"], "wrong_state");
  for (const std::string& path : {"/api/runs/987654/drawn", "/api/runs/abc/drawn"}) {
    const HttpResult r = get(path);
    EXPECT_EQ(r.status, 404) << path;
    EXPECT_EQ(error_of(r)["path"], "id") << path;
  }
}

}  // namespace
}  // namespace rrlab::testing

// What frames carry for drawing without kinematics in the browser: each
// link's nearest obstacle, the manipulability ellipsoid and the ghost arms'
// links, in live runs and in replays.
#include <cmath>

#include <functional>

#include "server_fixture.hpp"

namespace rrlab::testing {
namespace {

using nlohmann::json;

class StreamJson : public ServerTest {};

double norm3(double x, double y, double z) { return std::sqrt(x * x + y * y + z * z); }

// The next frame whose metrics name the link nearest an obstacle
// (min_distance_link >= 1; 0 would mean metrics not yet evaluated).
// The next frame whose nearest link is not the base's; `step` (a paused
// live run's single step) runs before each read.
json stepped_frame(WsClient& ws, const std::function<void()>& step = {}) {
  for (int i = 0; i < 500; ++i) {
    if (step) step();
    auto frame = ws.read_type("frame");
    if (!frame) break;
    if ((*frame)["metrics"]["min_distance_link"].get<int>() >= 1) return *frame;
  }
  ADD_FAILURE() << "no stepped frame";
  return {};
}

// nearest: one entry per link, 9 numbers, the minimum one at metrics.min_distance_link.
void expect_nearest_matches_metrics(const json& frame, const json& snapshot) {
  ASSERT_TRUE(frame.contains("nearest")) << frame.dump();
  const json& nearest = frame["nearest"];
  const json& links = frame["links"];
  ASSERT_EQ(nearest.size(), links.size());
  const int min_link = frame["metrics"]["min_distance_link"];
  const double min_distance = frame["metrics"]["min_distance"];
  double smallest = 1e300;
  for (size_t l = 0; l < nearest.size(); ++l) {
    const json& e = nearest[l];
    ASSERT_EQ(e.size(), 9u);
    EXPECT_EQ(e[0].get<int>(), int(l) + 1);
    EXPECT_GE(e[1].get<int>(), 0);
    EXPECT_LT(e[1].get<size_t>(), snapshot["obstacles"].size());
    const double distance = e[2];
    smallest = std::min(smallest, distance);
    // the gap between the two points is the distance plus the link's radius (no penetration here)
    const double radius = snapshot["model"]["links"][l]["radius"];
    if (distance > 0) {
      const double gap = norm3(e[3].get<double>() - e[6].get<double>(), e[4].get<double>() - e[7].get<double>(),
                               e[5].get<double>() - e[8].get<double>());
      EXPECT_NEAR(gap, distance + radius, 1e-5) << e.dump();
    }
    if (int(l) + 1 == min_link) {
      EXPECT_NEAR(distance, min_distance, 1e-6 * std::abs(min_distance)) << e.dump() << " vs " << min_distance;
    }
  }
  EXPECT_NEAR(smallest, min_distance, 1e-6 * std::abs(min_distance));
}

// ellipsoid: centred at the end-effector; for an xy task two semi-axes in the
// plane whose lengths multiply to the manipulability, the third zero.
void expect_planar_ellipsoid(const json& frame) {
  ASSERT_TRUE(frame.contains("ellipsoid")) << frame.dump();
  const json& e = frame["ellipsoid"];
  const json& tip = frame["links"].back();
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(e["centre"][i].get<double>(), tip[3 + i].get<double>(), 1e-6);
  ASSERT_EQ(e["axes"].size(), 3u);
  double product = 1;
  int non_zero = 0;
  double previous = 1e300;
  for (const json& axis : e["axes"]) {
    ASSERT_EQ(axis.size(), 3u);
    const double length = norm3(axis[0], axis[1], axis[2]);
    EXPECT_LE(length, previous * (1 + 1e-6));  // longest first
    previous = length;
    EXPECT_NEAR(axis[2].get<double>(), 0.0, 1e-12);  // planar: in the x-y plane
    if (length > 1e-9) {
      product *= length;
      ++non_zero;
    }
  }
  EXPECT_EQ(non_zero, 2);
  const double manipulability = frame["metrics"]["manipulability"];
  EXPECT_NEAR(product, manipulability, 1e-5 * manipulability);
  // the two axes are perpendicular
  const json& a = e["axes"][0];
  const json& b = e["axes"][1];
  const double dot = a[0].get<double>() * b[0].get<double>() + a[1].get<double>() * b[1].get<double>();
  EXPECT_NEAR(dot, 0.0, 1e-5 * product + 1e-12);
}

TEST_F(StreamJson, LiveFramesCarryNearestObstaclesAndTheEllipsoid) {
  // paused and stepped by hand: the run cannot end before the test reads it
  const std::int64_t id = start_live({{"scenario", "01_planar7_obstacles"}, {"paused", true}});
  WsClient ws(port(), "/ws/runs/" + std::to_string(id));
  const auto snapshot = ws.read_type("snapshot");
  ASSERT_TRUE(snapshot);
  ASSERT_EQ((*snapshot)["obstacles"].size(), 3u);
  for (int i = 0; i < 5; ++i) {
    const json frame = stepped_frame(ws, [&] {
      EXPECT_EQ(send("POST", "/api/runs/" + std::to_string(id) + "/control", {{"action", "step"}}).status, 200);
    });
    ASSERT_FALSE(frame.is_null());
    expect_nearest_matches_metrics(frame, *snapshot);
    expect_planar_ellipsoid(frame);
    EXPECT_FALSE(frame.contains("overlays") && frame["overlays"].contains("ghost_links") &&
                 !frame["overlays"]["ghost_links"].empty());  // closest_point draws no ghosts
  }
  EXPECT_EQ(send("POST", "/api/runs/" + std::to_string(id) + "/control", {{"action", "stop"}}).status, 200);
  wait_ended(id);
}

// A mesh obstacle's snapshot entry carries its triangles for drawing (own
// frame, scaled), alongside the scenario keys; frames move it by position only.
TEST_F(StreamJson, SnapshotsCarryMeshObstacleTriangles) {
  const std::int64_t id = start_live({{"scenario", "43_urdf_iiwa14_mesh_obstacle"}, {"paused", true}});
  WsClient ws(port(), "/ws/runs/" + std::to_string(id));
  const auto snapshot = ws.read_type("snapshot");
  ASSERT_TRUE(snapshot);
  const json& hoop = (*snapshot)["obstacles"][0];
  EXPECT_EQ(hoop["shape"], "mesh");
  EXPECT_EQ(hoop["file"], "meshes/torus.obj");
  EXPECT_EQ(hoop["scale"], json::array({2.0, 2.0, 2.0}));
  ASSERT_TRUE(hoop.contains("mesh")) << hoop.dump().substr(0, 400);
  EXPECT_EQ(hoop["mesh"]["triangles"].size(), 3u * 576u);
  EXPECT_EQ(hoop["mesh"]["vertices"].size(), 3u * 288u);
  double outer = 0;  // the torus scaled by 2: ring 0.2 m + tube 0.06 m
  for (size_t i = 0; i + 2 < hoop["mesh"]["vertices"].size(); i += 3)
    outer = std::max(outer, std::hypot(hoop["mesh"]["vertices"][i].get<double>(), hoop["mesh"]["vertices"][i + 1].get<double>()));
  EXPECT_NEAR(outer, 0.26, 1e-6);
  EXPECT_EQ(send("POST", "/api/runs/" + std::to_string(id) + "/control", {{"action", "stop"}}).status, 200);
  wait_ended(id);
}

TEST_F(StreamJson, MultiPreviewGhostsComeWithTheirLinks) {
  const json scenario = get("/api/scenarios/31_zhang_multi_preview").json();
  const std::int64_t id = start_live({{"scenario", "31_zhang_multi_preview"}, {"rate", 1}});
  WsClient ws(port(), "/ws/runs/" + std::to_string(id));
  const auto snapshot = ws.read_type("snapshot");
  ASSERT_TRUE(snapshot);
  const json base = (*snapshot)["model"]["base"];
  const size_t link_count = (*snapshot)["model"]["links"].size();
  const double first_length = scenario["robot"]["links"][0]["length"];
  std::optional<json> frame;
  for (int i = 0; i < 500; ++i) {
    frame = ws.read_type("frame");
    ASSERT_TRUE(frame);
    if (frame->contains("overlays") && !(*frame)["overlays"]["ghosts"].empty()) break;
  }
  ASSERT_TRUE(frame->contains("overlays")) << frame->dump();
  const json& ghosts = (*frame)["overlays"]["ghosts"];
  const json& ghost_links = (*frame)["overlays"]["ghost_links"];
  ASSERT_FALSE(ghosts.empty());
  ASSERT_EQ(ghost_links.size(), ghosts.size());
  for (size_t g = 0; g < ghosts.size(); ++g) {
    ASSERT_EQ(ghost_links[g].size(), link_count);
    const json& first = ghost_links[g][0];
    ASSERT_EQ(first.size(), 6u);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(first[i].get<double>(), base[i].get<double>(), 1e-9);  // starts at the base
    // a planar arm: the first link ends at base + length (cos q1, sin q1)
    const double q1 = ghosts[g][0];
    EXPECT_NEAR(first[3].get<double>(), base[0].get<double>() + first_length * std::cos(q1), 1e-5);
    EXPECT_NEAR(first[4].get<double>(), base[1].get<double>() + first_length * std::sin(q1), 1e-5);
    // links are chained
    for (size_t l = 1; l < link_count; ++l)
      for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(ghost_links[g][l][i].get<double>(), ghost_links[g][l - 1][3 + i].get<double>(), 1e-5);
  }
  EXPECT_TRUE((*frame)["nearest"].size() == link_count);  // one obstacle: the notched object
  EXPECT_EQ(send("POST", "/api/runs/" + std::to_string(id) + "/control", {{"action", "stop"}}).status, 200);
  wait_ended(id);
}

TEST_F(StreamJson, ReplayFramesCarryNearestObstaclesToo) {
  const HttpResult batch =
      send("POST", "/api/runs", {{"scenario", "01_planar7_obstacles"}, {"mode", "batch"}, {"steps", 200}});
  ASSERT_EQ(batch.status, 200);
  const std::string run = std::to_string(batch.json()["id"].get<long>());
  // slow: 200 frames over 20 s, so that the socket connects before the replay ends
  const HttpResult started = send("POST", "/api/runs/" + run + "/replay", {{"mode", "frames"}, {"speed", 0.1}});
  ASSERT_EQ(started.status, 201) << started.body;
  WsClient ws(port(), started.json()["ws"].get<std::string>());
  const auto snapshot = ws.read_type("snapshot");
  ASSERT_TRUE(snapshot);
  for (int i = 0; i < 3; ++i) {
    const json frame = stepped_frame(ws);
    ASSERT_FALSE(frame.is_null());
    expect_nearest_matches_metrics(frame, *snapshot);  // recomputed from the stored q
    expect_planar_ellipsoid(frame);
  }
}

TEST_F(StreamJson, NoObstaclesNoNearest) {
  const HttpResult batch =
      send("POST", "/api/runs", {{"scenario", "33_zhang_fig5_ellipsoids"}, {"mode", "batch"}, {"steps", 20}});
  ASSERT_EQ(batch.status, 200);
  const std::string run = std::to_string(batch.json()["id"].get<long>());
  const HttpResult started = send("POST", "/api/runs/" + run + "/replay", {{"mode", "frames"}, {"speed", 0.01}});
  ASSERT_EQ(started.status, 201) << started.body;
  WsClient ws(port(), started.json()["ws"].get<std::string>());
  const auto frame = ws.read_type("frame");
  ASSERT_TRUE(frame);
  EXPECT_FALSE(frame->contains("nearest"));
  EXPECT_TRUE(frame->contains("ellipsoid"));
}

}  // namespace
}  // namespace rrlab::testing

// Latest-wins fan-out: a client that never reads neither slows the run nor
// the other clients, and is dropped once its writes have stalled.
#include <iostream>

#include "server_fixture.hpp"

namespace rrlab::testing {
namespace {

using nlohmann::json;

class StalledClient : public ::testing::Test {};

TEST_F(StalledClient, DoesNotSlowTheRunOrOtherClients) {
  ServerProcess server("", {"--ws-stall-ms", "1000"});
  json scenario = small_scenario("circle", 600);
  const HttpResult started = http_json(server.port(), "POST", "/api/runs", {{"scenario", scenario}, {"rate", 1}});
  ASSERT_EQ(started.status, 201);
  const std::int64_t id = started.json()["id"];
  const std::string ws_path = "/ws/runs/" + std::to_string(id);

  WsClient stalled(server.port(), ws_path);  // never reads
  WsClient reader(server.port(), ws_path);
  ASSERT_TRUE(reader.read_type("snapshot"));
  const auto status = [&] { return http(server.port(), "GET", "/api/runs/" + std::to_string(id)).json()["live"]; };

  const json first = status();
  const auto start = std::chrono::steady_clock::now();
  int frames = 0;
  std::int64_t last_seq = -1;
  bool increasing = true;
  while (std::chrono::steady_clock::now() - start < std::chrono::seconds(3)) {
    auto frame = reader.read_type("frame", std::chrono::milliseconds(1000));
    ASSERT_TRUE(frame) << "the reading client stopped getting frames";
    const std::int64_t seq = (*frame)["seq"];
    increasing = increasing && seq > last_seq;
    last_seq = seq;
    ++frames;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const json last = status();
  // The run advances whatever the stalled client does, never faster than its
  // real-time rate (100 steps/s); the reader gets frames, never more than the
  // 60 Hz display rate, latest first. Only upper bounds on rates: a slow or
  // busy machine gives fewer steps and frames, never more.
  const long steps = last["step"].get<long>() - first["step"].get<long>();
  EXPECT_GT(steps, 0) << "the run did not advance while a client stalled";
  EXPECT_LT(double(steps) / seconds, 150.0);
  EXPECT_GE(frames, 3) << frames << " frames in " << seconds << " s";
  EXPECT_LT(frames / seconds, 70.0);
  std::cout << "fan-out: " << double(steps) / seconds << " steps/s, " << frames / seconds
            << " frames/s to the reader while another client stalled\n";
  EXPECT_TRUE(increasing);

  // The stalled client is dropped once its send queue has been stuck past --ws-stall-ms.
  int websockets = 2;
  rrlab::test::eventually(
      [&] { return (websockets = http(server.port(), "GET", "/api/health").json()["websockets"]) <= 1; },
      std::chrono::seconds(30), "the stalled client dropped");
  EXPECT_EQ(websockets, 1);
  EXPECT_TRUE(reader.read_type("frame", std::chrono::milliseconds(1000)));
}

}  // namespace
}  // namespace rrlab::testing

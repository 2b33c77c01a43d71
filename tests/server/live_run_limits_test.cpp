// Live runs nobody uses (Hardening III, item 4): one client opening live runs
// of a 3,600 s scenario and never connecting used to lock every client out
// for the hour (507 storage_quota: each reserved its whole duration's frames,
// 106,560,000 bytes). Now a live lane reserves a window ahead of what it
// stored, a run nobody watches or calls ends as abandoned, and an address
// holds a bounded number of live runs. The abandonment times are serve
// options, set to seconds here; waits poll with a deadline.
#include <chrono>
#include <thread>

#include "server_fixture.hpp"
#include "support/eventually.hpp"

namespace rrlab::testing {
namespace {

using nlohmann::json;

// A run as the list shows it: listing does not count as a call for the run.
json listed_run(unsigned short port, std::int64_t id) {
  for (const json& run : http(port, "GET", "/api/runs?limit=1000").json())
    if (run["id"] == id) return run;
  return {};
}

std::int64_t start_live_run(unsigned short port, double duration, bool paused = false) {
  const json body = {{"scenario", small_scenario("joystick", duration)}, {"rate", 1}, {"paused", paused}};
  const HttpResult r = http(port, "POST", "/api/runs", body.dump());
  EXPECT_EQ(r.status, 201) << r.body;
  return r.status == 201 ? r.json()["id"].get<std::int64_t>() : 0;
}

bool ended(const json& run) { return run.is_object() && run.value("status", "") == "stopped"; }

TEST(LiveRunLimits, AnHourLongLiveRunReservesAWindowNotItsDuration) {
  // 100 MiB in all: one hour of this arm's frames would not fit, a window does
  ServerProcess server("", {"--max-total-bytes", std::to_string(100 << 20)});
  for (int i = 0; i < 4; ++i) EXPECT_GT(start_live_run(server.port(), 3600), 0);
  EXPECT_EQ(server.stop(), 0);
}

TEST(LiveRunLimits, ARunNobodyWatchesOrCallsEndsAsAbandoned) {
  ServerProcess server("", {"--abandon-unwatched-s", "1", "--abandon-idle-s", "600"});
  const std::int64_t id = start_live_run(server.port(), 3600);
  const std::int64_t paused = start_live_run(server.port(), 3600, true);
  json run, paused_run;
  rrlab::test::eventually([&] { return ended(run = listed_run(server.port(), id)); }, std::chrono::seconds(60),
                          "the unused live run to end");
  rrlab::test::eventually([&] { return ended(paused_run = listed_run(server.port(), paused)); },
                          std::chrono::seconds(60), "the unused paused run to end");
  const json stored = http(server.port(), "GET", "/api/runs/" + std::to_string(id)).json();
  EXPECT_EQ(stored["summary"]["ended"], "abandoned") << stored.dump();
  EXPECT_GT(stored["frames"].get<long>(), 0);  // its frames are kept
  EXPECT_EQ(server.stop(), 0);
}

TEST(LiveRunLimits, ARunSteeredOverRestOnlyIsNotAbandoned) {
  ServerProcess server("", {"--abandon-unwatched-s", "1", "--abandon-idle-s", "2"});
  const std::int64_t id = start_live_run(server.port(), 3600);
  const std::string target = "/api/runs/" + std::to_string(id);
  // steered for longer than both limits, as the README's example steers one
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (std::chrono::steady_clock::now() < until) {
    const HttpResult r = http(server.port(), "POST", target + "/joystick", json{{"linear", {0.01, 0.0}}}.dump());
    ASSERT_EQ(r.status, 200) << r.body;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));  // the input rate of a person, not a wait for state
  }
  EXPECT_EQ(http(server.port(), "GET", target).json()["status"], "running");
  // and once nobody calls or watches it, the idle limit ends it
  json run;
  rrlab::test::eventually([&] { return ended(run = listed_run(server.port(), id)); }, std::chrono::seconds(60),
                          "the run left idle to end");
  EXPECT_EQ(server.stop(), 0);
}

TEST(LiveRunLimits, AnAddressBeyondItsLiveRunsEndsItsOldestUnwatchedOrIsRefused) {
  ServerProcess server("", {"--max-live-per-address", "2"});
  const std::int64_t first = start_live_run(server.port(), 3600, true);
  const std::int64_t second = start_live_run(server.port(), 3600, true);
  WsClient watch_second(server.port(), "/ws/runs/" + std::to_string(second));
  ASSERT_TRUE(watch_second.read_type("snapshot")) << "no snapshot";
  // a request refused for another reason (413: more frames than a run may store) ends no run
  const json too_long = {{"scenario", small_scenario("joystick", 3600)}, {"paused", true}, {"steps", 2000000}};
  EXPECT_EQ(http(server.port(), "POST", "/api/runs", too_long.dump()).status, 413);
  EXPECT_EQ(listed_run(server.port(), first)["status"], "paused");
  const std::int64_t third = start_live_run(server.port(), 3600, true);  // the first, unwatched, ends for it
  ASSERT_GT(third, 0);
  json run;
  rrlab::test::eventually([&] { return ended(run = listed_run(server.port(), first)); }, std::chrono::seconds(30),
                          "the oldest unwatched run to end");
  EXPECT_EQ(http(server.port(), "GET", "/api/runs/" + std::to_string(first)).json()["summary"]["ended"], "superseded");
  // both left are watched: a new one is refused, naming the limit
  WsClient watch_third(server.port(), "/ws/runs/" + std::to_string(third));
  ASSERT_TRUE(watch_third.read_type("snapshot"));
  const json body = {{"scenario", small_scenario("joystick", 3600)}, {"paused", true}};
  const HttpResult refused = http(server.port(), "POST", "/api/runs", body.dump());
  EXPECT_EQ(refused.status, 429) << refused.body;
  EXPECT_EQ(refused.json()["error"]["limit"], "max_live_per_address");
  // another address is not counted with this one; batch runs never are
  EXPECT_EQ(http_from("127.0.0.2", server.port(), "POST", "/api/runs", body.dump()).status, 201);
  const json batch = {{"scenario", small_scenario("circle", 1)}, {"mode", "batch"}};
  EXPECT_EQ(http(server.port(), "POST", "/api/runs", batch.dump()).status, 200);
  EXPECT_EQ(server.stop(), 0);
}

}  // namespace
}  // namespace rrlab::testing

// The run list while runs are live, and deleting runs: never while live,
// replayed or re-simulated.
#include <atomic>

#include "server_fixture.hpp"

namespace rrlab::testing {
namespace {

using nlohmann::json;

class RunRoutes : public ServerTest {
 protected:
  // The run with this id in GET /api/runs?query (null if absent).
  static json listed(const std::string& query, std::int64_t id) {
    for (const json& run : get("/api/runs?" + query).json())
      if (run["id"] == id) return run;
    return {};
  }
};

json scenario_named(const std::string& name, const std::string& trajectory = "joystick", double duration = 600) {
  json scenario = small_scenario(trajectory, duration);
  scenario["name"] = name;
  return scenario;
}

TEST_F(RunRoutes, ListShowsLiveStatusAndFramesStoredSoFar) {
  const std::int64_t id = start_live({{"scenario", scenario_named("list_live")}, {"rate", 1}});
  const std::string base = "/api/runs/" + std::to_string(id);
  json first, second;
  ASSERT_TRUE(rrlab::test::eventually(
      [&] {
        first = listed("scenario=list_live", id);
        return !first.is_null() && first["frames"].get<long>() > 0;
      },
      std::chrono::seconds(60), "the live run listed with frames stored"));
  EXPECT_EQ(first["status"], "running");
  ASSERT_TRUE(rrlab::test::eventually(
      [&] {
        second = listed("scenario=list_live&status=running&method=gpm&limit=5", id);
        return !second.is_null() && second["frames"].get<long>() > first["frames"].get<long>();
      },
      std::chrono::seconds(60), "the listed run's frames to grow"));
  EXPECT_GT(second["frames"].get<long>(), first["frames"].get<long>());
  EXPECT_GT(first["frames"].get<long>(), 0);

  ASSERT_EQ(send("POST", base + "/control", {{"action", "pause"}}).status, 200);
  EXPECT_EQ(listed("scenario=list_live&status=paused", id)["status"], "paused");
  EXPECT_TRUE(listed("scenario=list_live&status=running", id).is_null());
  EXPECT_TRUE(listed("scenario=list_live&offset=1", id).is_null());  // newest first: it is the only one

  // live (paused): not deletable
  const HttpResult refused = http(port(), "DELETE", base);
  EXPECT_EQ(refused.status, 409);
  EXPECT_EQ(error_of(refused)["code"], "wrong_state");
  EXPECT_NE(error_of(refused)["message"].get<std::string>().find("live"), std::string::npos);

  ASSERT_EQ(send("POST", base + "/control", {{"action", "stop"}}).status, 200);
  const json ended = wait_ended(id);
  EXPECT_EQ(listed("scenario=list_live", id)["frames"], ended["frames"]);
}

TEST_F(RunRoutes, DeleteRemovesTheRunItsFramesAndEvents) {
  const std::int64_t id = start_live({{"scenario", scenario_named("to_delete")}, {"rate", 0}, {"paused", true}});
  const std::string base = "/api/runs/" + std::to_string(id);
  ASSERT_EQ(send("POST", base + "/joystick", {{"linear", {0.01, 0}}}).status, 200);  // an event
  ASSERT_EQ(send("POST", base + "/control", {{"action", "step"}}).status, 200);
  ASSERT_EQ(send("POST", base + "/control", {{"action", "stop"}}).status, 200);
  wait_ended(id);
  ASSERT_EQ(get(base + "/events").json().size(), 1u);

  const HttpResult deleted = http(port(), "DELETE", base);
  ASSERT_EQ(deleted.status, 200) << deleted.body;
  EXPECT_EQ(deleted.json(), (json{{"deleted", id}}));
  EXPECT_EQ(get(base).status, 404);
  EXPECT_EQ(get(base + "/events").status, 404);
  EXPECT_EQ(get(base + "/frames").status, 404);
  EXPECT_TRUE(listed("scenario=to_delete", id).is_null());
  EXPECT_THROW(WsClient(port(), "/ws/runs/" + std::to_string(id)), std::runtime_error);  // gone from memory too

  const HttpResult again = http(port(), "DELETE", base);
  EXPECT_EQ(again.status, 404);
  EXPECT_EQ(error_of(again)["path"], "id");
  EXPECT_EQ(http(port(), "DELETE", "/api/runs/not-a-number").status, 404);
  EXPECT_EQ(http(port(), "DELETE", "/api/runs").status, 405);
}

TEST_F(RunRoutes, NotWhileAReplayPlays) {
  const HttpResult batch = send("POST", "/api/runs", {{"scenario", scenario_named("replayed", "circle", 60)},
                                                      {"mode", "batch"}});
  ASSERT_EQ(batch.status, 200);
  const std::int64_t id = batch.json()["id"];
  const std::string base = "/api/runs/" + std::to_string(id);
  const HttpResult replay = send("POST", base + "/replay", {{"mode", "frames"}, {"speed", 0.1}});
  ASSERT_EQ(replay.status, 201);
  const std::string rid = std::to_string(replay.json()["replay"].get<long>());

  const HttpResult refused = http(port(), "DELETE", base);
  EXPECT_EQ(refused.status, 409);
  EXPECT_NE(error_of(refused)["message"].get<std::string>().find("replay"), std::string::npos);

  // a paused replay is closed with the run
  ASSERT_EQ(send("POST", "/api/replays/" + rid + "/control", {{"action", "pause"}}).status, 200);
  EXPECT_EQ(http(port(), "DELETE", base).status, 200);
  EXPECT_EQ(get("/api/replays/" + rid).status, 404);
}

TEST_F(RunRoutes, NotWhileItIsResimulated) {
  // The DELETEs must arrive while the re-simulation runs: on a fast machine a
  // short one may end first, so a longer run is tried then (never skipped).
  bool checked = false;
  for (long steps = 3000; !checked && steps <= 48000; steps *= 4) {
    const HttpResult batch = send("POST", "/api/runs", {{"scenario", scenario_named("resimulated", "circle", steps)},
                                                        {"mode", "batch"}});
    ASSERT_EQ(batch.status, 200);
    const std::int64_t id = batch.json()["id"];
    const std::string base = "/api/runs/" + std::to_string(id);
    HttpResult answer;
    std::atomic<bool> answered{false};
    std::thread resimulation([&] {
      answer = send("POST", base + "/replay", {{"mode", "resimulate"}});
      answered = true;
    });
    // the re-simulation's own run appears (status running) once the job has begun
    // (or the re-simulation has answered already: then a longer one is tried)
    json target;
    rrlab::test::eventually(
        [&] {
          for (const json& run : get("/api/runs?scenario=resimulated").json())
            if (run["source_run"] == id && run["status"] == "running") target = run;
          return !target.is_null() || answered;
        },
        std::chrono::seconds(60), "the re-simulation to begin");
    const bool began = !target.is_null();
    const std::string target_path = began ? "/api/runs/" + std::to_string(target["id"].get<long>()) : "";
    const HttpResult source_refused = http(port(), "DELETE", base);
    const HttpResult target_refused = began ? http(port(), "DELETE", target_path) : HttpResult{};
    const bool still_running = began && get(target_path).json()["status"] == "running";
    resimulation.join();
    ASSERT_EQ(answer.status, 200) << answer.body;
    if (still_running) {
      checked = true;
      EXPECT_EQ(source_refused.status, 409) << source_refused.body;
      EXPECT_NE(error_of(source_refused)["message"].get<std::string>().find("re-simulated"), std::string::npos);
      EXPECT_EQ(target_refused.status, 409) << target_refused.body;
    }
    // once it has answered, both may go at once (the job lets go of the source before it answers)
    if (source_refused.status != 200) EXPECT_EQ(http(port(), "DELETE", base).status, 200);
    if (began && target_refused.status != 200) EXPECT_EQ(http(port(), "DELETE", target_path).status, 200);
  }
  EXPECT_TRUE(checked) << "no re-simulation, up to 48000 steps, was still running when the DELETEs arrived";
}

}  // namespace
}  // namespace rrlab::testing

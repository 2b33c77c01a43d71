// Quotas (serve --max-run-frames, --max-run-bytes, --max-run-cost,
// --max-total-bytes, --max-scenarios): a request beyond one is refused before
// anything is stored or started, with an error naming the limit and the
// numbers; limits reached during a live run stop its storage, not the run.
// Each test starts its own server with the limits it tests.
#include <chrono>
#include <thread>
#include "server_fixture.hpp"

namespace rrlab::testing {
namespace {

using nlohmann::json;

HttpResult post(const ServerProcess& server, const std::string& target, const json& body) {
  return http(server.port(), "POST", target, body.dump());
}

json batch(const json& scenario, long steps) {
  return {{"scenario", scenario}, {"mode", "batch"}, {"steps", steps}};
}

std::size_t stored_runs(const ServerProcess& server) { return http(server.port(), "GET", "/api/runs").json().size(); }

// small_scenario: 4 joints, 1 obstacle (cost 4 x 2 = 8 per step).
json circle() { return small_scenario("circle", 600); }

// The bytes of one stored frame of circle() (from a stored run).
std::int64_t frame_bytes_of(const ServerProcess& server) {
  const HttpResult r = post(server, "/api/runs", batch(circle(), 10));
  EXPECT_EQ(r.status, 200) << r.body;
  const json run = http(server.port(), "GET", "/api/runs/" + std::to_string(r.json().at("id").get<long>())).json();
  EXPECT_EQ(run.at("frames"), 10);
  return run.at("frame_bytes").get<std::int64_t>() / 10;
}

TEST(Quotas, StepsBeyondMaxRunFramesAre413AndNothingIsStored) {
  ServerProcess server("", {"--max-run-frames", "850"});
  const HttpResult refused = post(server, "/api/runs", batch(circle(), 851));
  ASSERT_EQ(refused.status, 413) << refused.body;
  const json error = error_of(refused);
  EXPECT_EQ(error["code"], "run_too_large");
  EXPECT_EQ(error["limit"], "max_run_frames");
  EXPECT_EQ(error["requested"], 851);
  EXPECT_EQ(error["allowed"], 850);
  EXPECT_EQ(error["path"], "steps");
  EXPECT_NE(error["message"].get<std::string>().find("--max-run-frames"), std::string::npos);
  EXPECT_EQ(stored_runs(server), 0u);

  const HttpResult accepted = post(server, "/api/runs", batch(circle(), 850));
  ASSERT_EQ(accepted.status, 200) << accepted.body;
  EXPECT_EQ(accepted.json()["summary"]["frames_stored"], 850);
  EXPECT_FALSE(accepted.json()["summary"].contains("storage_stopped"));
}

// A live run's resets take it past its estimate: the per-run limit still
// holds, storage stops at it, the run goes on and its summary says why.
TEST(Quotas, ALiveRunStopsStoringAtMaxRunFramesAndSaysWhy) {
  ServerProcess server("", {"--max-run-frames", "850"});
  // 800 steps; paused once past step 200, reset and started again: 1000 or more
  const HttpResult started = post(server, "/api/runs", {{"scenario", small_scenario("circle", 8.0)}, {"rate", 1}});
  ASSERT_EQ(started.status, 201) << started.body;
  const std::string base = "/api/runs/" + std::to_string(started.json()["id"].get<long>());
  ASSERT_TRUE(rrlab::test::eventually(
      [&] { return http(server.port(), "GET", base).json()["live"].value("step", 0L) >= 200; },
      std::chrono::seconds(60), "the run at step 200"));
  ASSERT_EQ(post(server, base + "/control", {{"action", "pause"}}).status, 200)
      << "the run ended before it could be paused";
  ASSERT_EQ(post(server, base + "/control", {{"action", "reset"}}).status, 200);
  ASSERT_EQ(post(server, base + "/control", {{"action", "start"}}).status, 200);
  json run;
  rrlab::test::eventually(
      [&] {
        run = http(server.port(), "GET", base).json();
        return run["status"] == "completed" || run["status"] == "failed";
      },
      std::chrono::seconds(60), "the run to end");
  ASSERT_EQ(run["status"], "completed") << run.dump();
  EXPECT_GT(run["live"]["frames"].get<long>(), 850);  // steps taken over the reset (about 1000)
  EXPECT_EQ(run["frames"], 850);
  EXPECT_EQ(run["summary"]["frames_stored"], 850);
  const std::string why = run["summary"]["storage_stopped"];
  EXPECT_NE(why.find("max_run_frames"), std::string::npos) << why;
  EXPECT_NE(why.find("850"), std::string::npos) << why;
}

TEST(Quotas, BytesBeyondMaxRunBytesAre413) {
  ServerProcess server("", {"--max-run-bytes", "100000"});
  const std::int64_t bpf = frame_bytes_of(server);
  EXPECT_GT(bpf, 100);  // 4 joints: 264 bytes
  const long steps = long(100000 / bpf) + 1;
  const HttpResult refused = post(server, "/api/runs", batch(circle(), steps));
  ASSERT_EQ(refused.status, 413) << refused.body;
  const json error = error_of(refused);
  EXPECT_EQ(error["limit"], "max_run_bytes");
  EXPECT_EQ(error["requested"], steps * bpf);
  EXPECT_EQ(error["allowed"], 100000);
  EXPECT_EQ(error["frame_bytes"], bpf);
  EXPECT_EQ(error["frames"], steps);
  EXPECT_EQ(stored_runs(server), 1u);  // the measuring run only
  EXPECT_EQ(post(server, "/api/runs", batch(circle(), steps - 1)).status, 200);
}

TEST(Quotas, TheCostEstimateIsRefusedBeforeAnythingStarts) {
  ServerProcess server("", {"--max-run-cost", "40000"});
  // DOF x (obstacles + 1) x steps = 4 x 2 x 5001 = 40008
  const HttpResult refused = post(server, "/api/runs", batch(circle(), 5001));
  ASSERT_EQ(refused.status, 413) << refused.body;
  json error = error_of(refused);
  EXPECT_EQ(error["code"], "run_too_large");
  EXPECT_EQ(error["limit"], "max_run_cost");
  EXPECT_EQ(error["requested"].get<double>(), 40008.0);
  EXPECT_EQ(error["allowed"].get<double>(), 40000.0);
  EXPECT_NE(error["message"].get<std::string>().find("4 x (1 + 1) x 5001"), std::string::npos) << error["message"];
  // a live run is estimated by its scenario's steps (600 s / 0.01 s = 60000: cost 480000)
  const HttpResult live = post(server, "/api/runs", {{"scenario", circle()}});
  ASSERT_EQ(live.status, 413) << live.body;
  EXPECT_EQ(error_of(live)["requested"].get<double>(), 480000.0);
  // a comparison costs the sum of its runs: 2 x 4 x 2 x 2501 = 40016
  const json methods = json::array({{{"name", "gpm"}}, {{"name", "pinv"}}});
  const HttpResult compare =
      post(server, "/api/compare", {{"scenario", circle()}, {"methods", methods}, {"steps", 2501}, {"mode", "batch"}});
  ASSERT_EQ(compare.status, 413) << compare.body;
  EXPECT_EQ(error_of(compare)["requested"].get<double>(), 40016.0);
  EXPECT_EQ(stored_runs(server), 0u);

  EXPECT_EQ(post(server, "/api/runs", batch(circle(), 5000)).status, 200);
  const HttpResult pair =
      post(server, "/api/compare", {{"scenario", circle()}, {"methods", methods}, {"steps", 2500}, {"mode", "batch"}});
  EXPECT_LT(pair.status, 300) << pair.body;
}

// The total is SUM(frame_bytes) at start, kept current by runs and deletions.
TEST(Quotas, TheTotalIsCountedFromTheDatabaseAndFreedByDeletion) {
  const std::string dir = temp_dir();
  const std::string db = dir + "/quota.db";
  std::int64_t bpf = 0;
  std::int64_t first = 0;
  {
    ServerProcess server(db, {"--max-total-bytes", "150000"});
    bpf = frame_bytes_of(server);  // 10 frames stored
    const HttpResult a = post(server, "/api/runs", batch(circle(), 300));
    ASSERT_EQ(a.status, 200) << a.body;
    first = a.json()["id"];
    const HttpResult refused = post(server, "/api/runs", batch(circle(), 400));
    ASSERT_EQ(refused.status, 507) << refused.body;
    const json error = error_of(refused);
    EXPECT_EQ(error["code"], "storage_quota");
    EXPECT_EQ(error["limit"], "max_total_bytes");
    EXPECT_EQ(error["requested"], 400 * bpf);
    EXPECT_EQ(error["stored"], 310 * bpf);
    EXPECT_EQ(error["allowed"], 150000);
    EXPECT_EQ(stored_runs(server), 2u);
    ASSERT_EQ(server.stop(), 0);
  }
  ServerProcess server(db, {"--max-total-bytes", "150000"});
  const HttpResult refused = post(server, "/api/runs", batch(circle(), 400));
  ASSERT_EQ(refused.status, 507) << refused.body;
  EXPECT_EQ(error_of(refused)["stored"], 310 * bpf);  // counted at start
  ASSERT_EQ(http(server.port(), "DELETE", "/api/runs/" + std::to_string(first)).status, 200);
  const HttpResult accepted = post(server, "/api/runs", batch(circle(), 400));
  ASSERT_EQ(accepted.status, 200) << accepted.body;
  const HttpResult again = post(server, "/api/runs", batch(circle(), 400));
  ASSERT_EQ(again.status, 507) << again.body;
  EXPECT_EQ(error_of(again)["stored"], 410 * bpf);
}

// A re-simulation stores a copy of its run's frames: it is admitted against
// --max-total-bytes like a run (before, four re-simulations of one run stored
// 4.3 times the quota).
TEST(Quotas, ReSimulationsCountAgainstTheTotal) {
  ServerProcess server("", {"--max-total-bytes", "150000"});
  const std::int64_t bpf = frame_bytes_of(server);  // 10 frames stored
  const HttpResult run = post(server, "/api/runs", batch(circle(), 300));
  ASSERT_EQ(run.status, 200) << run.body;
  const std::string replay = "/api/runs/" + std::to_string(run.json()["id"].get<long>()) + "/replay";
  // 310 frames stored; a copy of 300 would take the total past 150000 bytes
  ASSERT_GT(610 * bpf, 150000) << "the frames got smaller: make the run longer";
  const HttpResult refused = post(server, replay, {{"mode", "resimulate"}});
  ASSERT_EQ(refused.status, 507) << refused.body;
  EXPECT_EQ(error_of(refused)["limit"], "max_total_bytes");
  EXPECT_EQ(stored_runs(server), 2u);
}

// Sweeps and costly methods are admitted by what they cost: before, a sweep of
// 1e7-step runs was accepted (202), and a multi_preview comparison with
// population 200 was estimated as cheaply as pinv.
TEST(Quotas, SweepsAndCostlyMethodsAreAdmittedByTheirCost) {
  ServerProcess server;
  json seeds = json::array();
  for (int s = 1; s <= 100; ++s) seeds.push_back(s);
  const json sweep = {{"name", "too_big"}, {"scenarios", {"01_planar7_obstacles"}}, {"methods", {"pinv"}},
                      {"seeds", seeds}, {"steps", 10000000}, {"success", {{"collision", false}}}};
  const HttpResult refused_sweep = post(server, "/api/sweeps", sweep);  // 100 x 7 x 4 x 1e7 = 2.8e10
  ASSERT_EQ(refused_sweep.status, 413) << refused_sweep.body;
  EXPECT_EQ(error_of(refused_sweep)["limit"], "max_run_cost");
  EXPECT_NE(error_of(refused_sweep)["message"].get<std::string>().find("summed over 100 runs"), std::string::npos);

  const json costly = {{"name", "multi_preview"}, {"params", {{"population", 200}}}};
  const HttpResult refused_compare = post(server, "/api/compare",
                                          {{"scenario", "01_planar7_obstacles"}, {"methods", {costly, "pinv"}},
                                           {"steps", 200000}, {"mode", "batch"}});
  ASSERT_EQ(refused_compare.status, 413) << refused_compare.body;  // 7 x 4 x 2e5 x (7201 + 1) = 4.0e10
  EXPECT_EQ(error_of(refused_compare)["limit"], "max_run_cost");
  EXPECT_NE(error_of(refused_compare)["message"].get<std::string>().find("x 7201"), std::string::npos)
      << error_of(refused_compare)["message"];
  // the same comparison of two cheap methods fits
  const HttpResult cheap = post(server, "/api/compare",
                                {{"scenario", "01_planar7_obstacles"}, {"methods", {"dls", "pinv"}}, {"steps", 2000},
                                 {"mode", "batch"}});
  EXPECT_EQ(cheap.status, 200) << cheap.body;
}

TEST(Quotas, StoredScenariosAreCappedAndListedAsPagedSummaries) {
  ServerProcess server("", {"--max-scenarios", "2"});
  const auto get = [&](const std::string& target) { return http(server.port(), "GET", target); };
  const json first_page = get("/api/scenarios").json();
  const std::int64_t builtin = first_page["total"];
  EXPECT_GE(builtin, 3);

  json long_one = circle();
  long_one["name"] = "zz_long";
  long_one["description"] = std::string(300, 'd');
  // a 900 KB source once made each page of the list carry it whole (100 such: 100 MB a page)
  long_one["source"] = std::string(900 * 1024, 's');
  json other = circle();
  other["name"] = "zz_other";
  ASSERT_EQ(post(server, "/api/scenarios", long_one).status, 201);
  ASSERT_EQ(post(server, "/api/scenarios", other).status, 201);
  json third = circle();
  third["name"] = "zz_third";
  const HttpResult refused = post(server, "/api/scenarios", third);
  ASSERT_EQ(refused.status, 507) << refused.body;
  EXPECT_EQ(error_of(refused)["code"], "storage_quota");
  EXPECT_EQ(error_of(refused)["limit"], "max_scenarios");
  EXPECT_EQ(error_of(refused)["stored"], 2);
  EXPECT_EQ(error_of(refused)["allowed"], 2);
  EXPECT_EQ(get("/api/scenarios/zz_third").status, 404);
  EXPECT_EQ(post(server, "/api/scenarios", other).status, 409);  // an existing name is still 409

  // pages of 2 cover the catalogue once, files first, stored ones last
  std::vector<std::string> names;
  for (int offset = 0;; offset += 2) {
    const json page = get("/api/scenarios?limit=2&offset=" + std::to_string(offset)).json();
    EXPECT_EQ(page["total"], builtin + 2);
    EXPECT_EQ(page["limit"], 2);
    EXPECT_EQ(page["offset"], offset);
    if (page["scenarios"].empty()) break;
    EXPECT_LE(page["scenarios"].size(), 2u);
    for (const json& s : page["scenarios"]) names.push_back(s["name"]);
  }
  ASSERT_EQ(std::int64_t(names.size()), builtin + 2);
  EXPECT_EQ(names[names.size() - 2], "zz_long");
  EXPECT_EQ(names.back(), "zz_other");

  const json tail = get("/api/scenarios?offset=" + std::to_string(builtin)).json()["scenarios"];
  ASSERT_EQ(tail.size(), 2u);
  const json& summary = tail[0];
  EXPECT_EQ(summary["builtin"], false);
  EXPECT_EQ(summary["kind"], "planar");
  EXPECT_EQ(summary["dof"], 4);
  EXPECT_EQ(summary["obstacles"], 1);
  EXPECT_EQ(summary["bytes"], long_one.dump().size());
  EXPECT_FALSE(summary.contains("robot"));  // a summary, not the scenario
  const std::string excerpt = summary["description"];
  EXPECT_EQ(excerpt, std::string(200, 'd') + "\u2026");
  EXPECT_EQ(summary["source"], std::string(200, 's') + "\u2026");
  EXPECT_LT(get("/api/scenarios").body.size(), 64u * 1024u) << "the list carries more than summaries";
  EXPECT_EQ(get("/api/scenarios/zz_long").json()["source"].get<std::string>().size(), 900u * 1024u);  // whole here

  EXPECT_EQ(get("/api/scenarios?limit=0").status, 400);
  EXPECT_EQ(get("/api/scenarios?limit=1001").status, 400);
  EXPECT_EQ(get("/api/scenarios?offset=-1").status, 400);
}

// Found in review: a sweep run stores no frames, and its re-simulation steps as
// far as its summary says; it was admitted as a run of 0 frames, past every limit.
TEST(Quotas, ReSimulatingAFramelessSweepRunIsAdmittedForTheStepsItWillStore) {
  ServerProcess server("", {"--max-run-frames", "100"});
  const json spec = {{"name", "frameless-quota"},
                     {"scenarios", json::array({"01_planar7_obstacles"})},
                     {"methods", json::array({"dls"})},
                     {"steps", 150},
                     {"success", {{"max_tracking_error", 0.01}}}};
  const HttpResult started = post(server, "/api/sweeps", spec);
  ASSERT_EQ(started.status, 202) << started.body;
  const std::string status = "/api/sweeps/" + std::to_string(started.json()["id"].get<long>());
  json sweep;
  rrlab::test::eventually([&] { return (sweep = http(server.port(), "GET", status).json())["status"] != "running"; },
                          std::chrono::seconds(60), "the sweep to end");
  ASSERT_EQ(sweep["status"], "completed") << sweep;
  const json runs = http(server.port(), "GET", status + "/runs").json()["runs"];
  ASSERT_EQ(runs.size(), 1u);
  const std::string run = std::to_string(runs[0]["run"].get<long>());
  EXPECT_EQ(runs[0]["frames"], 0);
  const HttpResult refused = post(server, "/api/runs/" + run + "/replay", {{"mode", "resimulate"}});
  ASSERT_EQ(refused.status, 413) << refused.body;
  EXPECT_EQ(error_of(refused)["limit"], "max_run_frames");
  EXPECT_EQ(error_of(refused)["requested"], 150);
}

}  // namespace
}  // namespace rrlab::testing

// Sweeps over REST: start, progress, report, stop; specs are checked like the
// command line's (422 naming the JSON path) and may not name files.
#include <algorithm>
#include <chrono>
#include <thread>

#include "server_fixture.hpp"

namespace rrlab::testing {
namespace {

using nlohmann::json;

class SweepRoutes : public ServerTest {
 protected:
  static json spec(const std::string& name, int count) {
    return {{"name", name},
            {"scenarios", json::array({json{{"generator", "planar_clutter"}, {"count", count}, {"seed", 3}},
                                       "01_planar7_obstacles"})},
            {"methods", json::array({"pinv", json{{"name", "dls"}, {"params", {{"lambda", json::array({0.01, 0.1})}}}}})},
            {"success", {{"max_tracking_error", 0.01}}},
            {"steps", 200}};
  }
  json wait_ended(std::int64_t id) {
    json s;
    const bool ended = rrlab::test::eventually(
        [&] { return (s = get("/api/sweeps/" + std::to_string(id)).json())["status"] != "running"; },
        std::chrono::seconds(60), "sweep " + std::to_string(id) + " to end");
    return ended ? s : json{};
  }
};

// Found while fuzzing POST /api/sweeps: the spec was expanded before its size
// was checked, so 1 KB naming 3 x 10^8 runs made the server take gigabytes
// (12 million runs: 15 s and 2 GB) before answering 422. Now counted first.
TEST_F(SweepRoutes, AHugeSpecIsRefusedBeforeItIsExpanded) {
  json huge = spec("rest-huge", 1);
  huge["scenarios"] = json::array();
  for (int i = 0; i < 100; ++i) huge["scenarios"].push_back({{"generator", "planar_clutter"}, {"count", 1000000}, {"seed", i}});
  const HttpResult refused = send("POST", "/api/sweeps", huge);
  EXPECT_EQ(refused.status, 422) << refused.body;
  EXPECT_NE(refused.body.find("expands to 300000000 runs"), std::string::npos) << refused.body;
  EXPECT_EQ(get("/api/health").status, 200);  // the server is still there
  // each generator entry's first case is generated to admit the sweep: at most 64 entries
  json many = spec("rest-many", 1);
  many["scenarios"] = json::array();
  for (int i = 0; i < 65; ++i) many["scenarios"].push_back({{"generator", "planar_clutter"}, {"count", 1}, {"seed", i}});
  const HttpResult too_many = send("POST", "/api/sweeps", many);
  EXPECT_EQ(too_many.status, 422) << too_many.body;
  EXPECT_NE(too_many.body.find("65 generator entries; over REST at most 64"), std::string::npos) << too_many.body;
}

TEST_F(SweepRoutes, RunsToTheEndAndAnswersWithItsReport) {
  const HttpResult started = send("POST", "/api/sweeps", spec("rest-small", 3));
  ASSERT_EQ(started.status, 202) << started.body;
  const json head = started.json();
  EXPECT_EQ(head["total"], (3 + 1) * 3);  // 4 scenarios x 3 method configurations
  const json done = wait_ended(head["id"].get<std::int64_t>());
  EXPECT_EQ(done["status"], "completed");
  EXPECT_EQ(done["done"], 12);
  EXPECT_EQ(done["failed"], 0);
  const json& report = done["report"];
  ASSERT_EQ(report["ranking"].size(), 3u);
  size_t runs = 0;
  for (const json& g : report["groups"]) {
    runs += g["n"].get<size_t>();
    EXPECT_LE(g["success_interval"][0].get<double>(), g["success_rate"].get<double>());
    EXPECT_GE(g["success_interval"][1].get<double>(), g["success_rate"].get<double>());
  }
  EXPECT_EQ(runs, 12u);
  EXPECT_EQ(report["pairs"].size(), 3u);
  // its runs are stored batch runs like any other
  EXPECT_GE(get("/api/runs?limit=100").json().size(), 12u);
  // the list knows it
  const json list = get("/api/sweeps").json();
  ASSERT_EQ(list.size(), 1u);
  EXPECT_EQ(list[0]["name"], "rest-small");
}

TEST_F(SweepRoutes, StopsOnRequestKeepingWhatItStored) {
  const HttpResult started = send("POST", "/api/sweeps", spec("rest-stop", 400));
  ASSERT_EQ(started.status, 202) << started.body;
  const std::int64_t id = started.json()["id"];
  const HttpResult stop = send("POST", "/api/sweeps/" + std::to_string(id) + "/control", json{{"action", "stop"}});
  EXPECT_EQ(stop.status, 200) << stop.body;
  const json ended = wait_ended(id);
  EXPECT_EQ(ended["status"], "stopped");
  EXPECT_LT(ended["done"].get<int>(), ended["total"].get<int>());
  // stop is the one control action
  EXPECT_EQ(send("POST", "/api/sweeps/" + std::to_string(id) + "/control", json{{"action", "pause"}}).status, 400);
}

TEST_F(SweepRoutes, BadSpecsAreNamedByTheirPath) {
  json bad = spec("rest-bad", 2);
  bad["methods"][1]["params"]["lambda"][1] = -1;
  HttpResult r = send("POST", "/api/sweeps", bad);
  EXPECT_EQ(r.status, 422);
  EXPECT_EQ(r.json()["error"]["path"], "methods[1].params.lambda[1]") << r.body;

  json file = spec("rest-file", 2);
  file["scenarios"][1] = "../scenarios/01_planar7_obstacles.json";
  r = send("POST", "/api/sweeps", file);
  EXPECT_EQ(r.status, 422);
  EXPECT_EQ(r.json()["error"]["path"], "scenarios[1]") << r.body;
  // nor through a perturbation family: only a catalogue scenario is perturbed over REST
  file["scenarios"][1] = json{{"perturb", "../scenarios/01_planar7_obstacles.json"}, {"count", 2}};
  r = send("POST", "/api/sweeps", file);
  EXPECT_EQ(r.status, 422);
  EXPECT_EQ(r.json()["error"]["path"], "scenarios[1].perturb") << r.body;
  file["scenarios"][1] = json{{"perturb", "/etc/hostname"}, {"count", 2}};
  EXPECT_EQ(send("POST", "/api/sweeps", file).status, 422);

  json huge = spec("rest-huge", 1);
  huge["scenarios"][0]["count"] = 1000000;
  r = send("POST", "/api/sweeps", huge);
  EXPECT_EQ(r.status, 422) << r.body;

  EXPECT_EQ(get("/api/sweeps/99").status, 404);
  EXPECT_EQ(send("POST", "/api/sweeps", json::array()).status, 422);
}

TEST_F(SweepRoutes, ItsRunsArePagedByCellAndSayWhichSweepAndCaseTheyBelongTo) {
  const HttpResult started = send("POST", "/api/sweeps", spec("rest-cells", 2));
  ASSERT_EQ(started.status, 202) << started.body;
  const std::int64_t id = started.json()["id"].get<std::int64_t>();
  const json done = wait_ended(id);
  ASSERT_EQ(done["status"], "completed");
  const std::string base = "/api/sweeps/" + std::to_string(id) + "/runs";

  const json all = get(base).json();
  EXPECT_EQ(all["total"], 9);  // 3 cases x 3 configurations
  EXPECT_EQ(all["runs"].size(), 9u);
  const json cell = get(base + "?family=planar_clutter&config=pinv").json();
  ASSERT_EQ(cell["total"], 2);
  for (const json& r : cell["runs"]) {
    EXPECT_EQ(r["family"], "planar_clutter");
    EXPECT_EQ(r["config"], "pinv");
    EXPECT_EQ(r["frames"], 0);  // a sweep stores summaries
    EXPECT_TRUE(r["min_distance"].is_number());
    EXPECT_EQ(r["case"].get<std::string>().rfind("gen:planar_clutter:", 0), 0u) << r["case"];
    // the run's own record names its sweep and case
    const json record = get("/api/runs/" + std::to_string(r["run"].get<std::int64_t>())).json();
    EXPECT_EQ(record["sweep"]["sweep"], "rest-cells");
    EXPECT_EQ(record["sweep"]["case"], r["case"]);
    EXPECT_EQ(record["sweep"]["config"], "pinv");
    EXPECT_EQ(record["sweep"]["success"], r["success"]);
  }
  // outcomes split the cell; pages and bad filters
  const int passed = get(base + "?outcome=pass").json()["total"].get<int>();
  const int failed = get(base + "?outcome=fail").json()["total"].get<int>();
  EXPECT_EQ(passed + failed, 9);
  EXPECT_EQ(get(base + "?limit=4&offset=8").json()["runs"].size(), 1u);
  // a scenario file is a family of its own, as the report names it
  const json file = get(base + "?family=file:01_planar7_obstacles").json();
  EXPECT_EQ(file["total"], 3);
  for (const json& r : file["runs"]) EXPECT_EQ(r["family"], "file:01_planar7_obstacles");
  EXPECT_EQ(error_of(get(base + "?outcome=maybe"))["path"], "outcome");
  EXPECT_EQ(error_of(get(base + "?limit=0"))["path"], "limit");
  EXPECT_EQ(get("/api/sweeps/999/runs").status, 404);
  // a run of no sweep says so
  const HttpResult plain = send("POST", "/api/runs", {{"scenario", "01_planar7_obstacles"}, {"mode", "batch"}, {"steps", 3}});
  const std::int64_t plain_id = plain.json()["id"].get<std::int64_t>();
  EXPECT_TRUE(get("/api/runs/" + std::to_string(plain_id)).json()["sweep"].is_null());
  // the run list filters by sweep: one sweep's runs, or the runs of none
  EXPECT_EQ(get("/api/runs?sweep=rest-cells&limit=100").json().size(), 9u);
  const json unswept = get("/api/runs?sweep=none&limit=1000").json();
  for (const json& r : unswept) EXPECT_TRUE(r["sweep"].is_null()) << r["id"];
  EXPECT_TRUE(std::any_of(unswept.begin(), unswept.end(), [&](const json& r) { return r["id"] == plain_id; }));
}

TEST_F(SweepRoutes, ValidateChecksASpecAsAStartWouldAndStartsNothing) {
  const HttpResult ok = send("POST", "/api/sweeps/validate", spec("rest-validated", 3));
  ASSERT_EQ(ok.status, 200) << ok.body;
  EXPECT_EQ(ok.json()["valid"], true);
  EXPECT_EQ(ok.json()["name"], "rest-validated");
  EXPECT_EQ(ok.json()["total"], 12);  // 4 scenarios x 3 configurations
  EXPECT_EQ(ok.json()["configurations"], 3);
  for (const json& started : get("/api/sweeps").json()) EXPECT_NE(started["name"], "rest-validated");  // nothing started
  json bad = spec("rest-validated", 3);
  bad["methods"] = json::array({"no_such_method"});
  const HttpResult refused = send("POST", "/api/sweeps/validate", bad);
  EXPECT_EQ(refused.status, 422) << refused.body;
  EXPECT_EQ(error_of(refused)["path"].get<std::string>().rfind("methods[0]", 0), 0u) << refused.body;
  bad = spec("rest-validated", 3);
  bad["scenarios"] = json::array({"../etc/passwd.json"});
  EXPECT_EQ(send("POST", "/api/sweeps/validate", bad).status, 422);  // never a path over REST
}

}  // namespace
}  // namespace rrlab::testing

// Sweeps that are large in configurations, over REST (Hardening III, items
// 1-3): a report grows linearly with its configurations and is built once,
// off the I/O threads; validating a grid of 100,000 configurations neither
// expands it nor keeps other clients waiting; a full disk stops a sweep with
// the reason, and runs can still be deleted. Sizes and scaling are asserted,
// and /api/health within 1 s; no timing that depends on the machine.
#include <algorithm>
#include <chrono>
#include <future>
#include <thread>
#include <vector>

#include "server_fixture.hpp"
#include "support/eventually.hpp"

namespace rrlab::testing {
namespace {

using nlohmann::json;

// One scenario, one step, `configurations` dls configurations (λ from 0.001 up).
json dls_grid(const std::string& name, int configurations) {
  json lambdas = json::array();
  for (int i = 1; i <= configurations; ++i) lambdas.push_back(0.001 * i);
  return {{"name", name},
          {"scenarios", json::array({"01_planar7_obstacles"})},
          {"methods", json::array({json{{"name", "dls"}, {"params", {{"lambda", lambdas}}}}})},
          {"success", {{"max_tracking_error", 0.01}}},
          {"steps", 1}};
}

json sweep_when_ended(unsigned short port, std::int64_t id) {
  json status;
  rrlab::test::eventually(
      [&] {
        status = http(port, "GET", "/api/sweeps/" + std::to_string(id)).json();
        return status.value("status", "") != "running";
      },
      std::chrono::minutes(5), "sweep " + std::to_string(id) + " to end");
  return status;
}

std::int64_t start_sweep(unsigned short port, const json& spec) {
  const HttpResult started = http(port, "POST", "/api/sweeps", spec.dump());
  EXPECT_EQ(started.status, 202) << started.body;
  return started.status == 202 ? started.json()["id"].get<std::int64_t>() : 0;
}

// How long /api/health takes to answer, in ms.
double health_ms(unsigned short port) {
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(http(port, "GET", "/api/health").status, 200);
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Was: every two configurations compared (700 configurations: 46 MB, 18.6 s,
// RSS +770 MB; 2,000: 373 MB). Now each is compared with its family's best
// and pinv; every pair only up to 32 configurations.
TEST(SweepScaling, AReportGrowsLinearlyWithItsConfigurationsAndIsBuiltOnce) {
  ServerProcess server;
  const std::int64_t small = start_sweep(server.port(), dls_grid("scale-100", 100));
  const std::int64_t large = start_sweep(server.port(), dls_grid("scale-400", 400));
  const json small_done = sweep_when_ended(server.port(), small);
  const json large_done = sweep_when_ended(server.port(), large);
  ASSERT_EQ(small_done["status"], "completed") << small_done.dump().substr(0, 500);
  ASSERT_EQ(large_done["status"], "completed") << large_done.dump().substr(0, 500);

  // two reports asked for at once, while health is polled
  auto first = std::async(std::launch::async, [&] { return http(server.port(), "GET", "/api/sweeps/" + std::to_string(large)); });
  auto second = std::async(std::launch::async, [&] { return http(server.port(), "GET", "/api/sweeps/" + std::to_string(large)); });
  double slowest_health = 0;
  for (int i = 0; i < 5; ++i) slowest_health = std::max(slowest_health, health_ms(server.port()));
  const HttpResult a = first.get(), b = second.get();
  ASSERT_EQ(a.status, 200);
  ASSERT_EQ(b.status, 200);
  EXPECT_EQ(a.body, b.body);  // one report, built once
  EXPECT_LT(slowest_health, 1000.0);

  const HttpResult small_report = http(server.port(), "GET", "/api/sweeps/" + std::to_string(small));
  const double ratio = double(a.body.size()) / double(small_report.body.size());
  EXPECT_LT(ratio, 4.6) << "4x the configurations cost " << ratio << "x the bytes";
  EXPECT_LT(a.body.size(), size_t(2) << 20);

  const json report = a.json()["report"];
  EXPECT_EQ(report["groups"].size(), 400u);
  EXPECT_EQ(report["ranking"].size(), 400u);
  EXPECT_TRUE(report["pairs"].empty());
  EXPECT_EQ(report["pairs_omitted"]["configurations"]["scale-400"], 400);
  EXPECT_EQ(report["comparisons"].size(), 399u);  // each against the family's best (no pinv in this sweep)
  EXPECT_FALSE(report.contains("truncated"));
  // a page of its runs, read in SQL
  const json page = http(server.port(), "GET", "/api/sweeps/" + std::to_string(large) + "/runs?limit=7&offset=390").json();
  EXPECT_EQ(page["total"], 400);
  EXPECT_EQ(page["runs"].size(), 7u);
  // and every run as CSV, whatever the table's cut: a header and one row per run
  const HttpResult csv = http(server.port(), "GET", "/api/sweeps/" + std::to_string(large) + "/runs?format=csv");
  ASSERT_EQ(csv.status, 200);
  EXPECT_EQ(csv.content_type, "text/csv");
  EXPECT_EQ(std::count(csv.body.begin(), csv.body.end(), '\n'), 401);
  EXPECT_EQ(csv.body.substr(0, csv.body.find('\n')),
            "run,key,case,config,family,success,failure_mode,failure_t,frames,steps,collided,min_distance,"
            "max_tracking_error,difficulty");
  const std::string one_config = "/api/sweeps/" + std::to_string(large) + "/runs?config=dls%7Blambda%3D0.002%7D";
  const HttpResult filtered = http(server.port(), "GET", one_config, "", "text/csv");
  EXPECT_EQ(std::count(filtered.body.begin(), filtered.body.end(), '\n'), 2) << filtered.body;
  EXPECT_EQ(server.stop(), 0);
}

// Was: expanded and admitted scenario by scenario: a 100,000-configuration
// grid held a worker 11.2 s; six in parallel kept another client's 10-step
// run waiting 31.4 s. Now counted, admitted once per scenario entry, and
// queued fairly between addresses.
TEST(SweepScaling, ValidatingAHugeGridLeavesOtherClientsServed) {
  ServerProcess server;
  json grid = dls_grid("huge-grid", 1000);
  json w0 = json::array();
  for (int i = 1; i <= 100; ++i) w0.push_back(0.001 * i);
  grid["methods"][0]["params"]["w0"] = w0;  // 1,000 x 100 configurations
  const HttpResult checked = http(server.port(), "POST", "/api/sweeps/validate", grid.dump());
  ASSERT_EQ(checked.status, 200) << checked.body;
  EXPECT_EQ(checked.json()["total"], 100000);
  EXPECT_EQ(checked.json()["configurations"], 100000);

  // one address validates six at once; another's batch run and health go on
  std::vector<std::future<HttpResult>> validations;
  for (int i = 0; i < 6; ++i)
    validations.push_back(std::async(std::launch::async, [&] {
      return http_from("127.0.0.2", server.port(), "POST", "/api/sweeps/validate", grid.dump());
    }));
  const json batch = {{"scenario", "01_planar7_obstacles"}, {"method", "dls"}, {"mode", "batch"}, {"steps", 10}};
  const HttpResult run = http(server.port(), "POST", "/api/runs", batch.dump());
  EXPECT_EQ(run.status, 200) << run.body;
  EXPECT_LT(health_ms(server.port()), 1000.0);
  for (auto& v : validations) {
    const HttpResult r = v.get();
    EXPECT_TRUE(r.status == 200 || r.status == 503) << r.status << " " << r.body;  // 503: its address's share of the queue
  }
  EXPECT_EQ(server.stop(), 0);
}

// Was: on a full disk a REST sweep stayed "running", computing run after run
// that could not be stored (2,755 of them, 45 % CPU). Now the first one stops it.
TEST(SweepScaling, AFullDiskStopsARestSweepWithTheReasonAndRunsCanBeDeleted) {
  ServerProcess server("", {"--test-db-max-pages", "600"});
  json spec = dls_grid("filling", 500);
  spec["seeds"] = json::array({1, 2, 3, 4, 5, 6, 7, 8});  // 4,000 runs: far more than 600 pages hold
  const std::int64_t id = start_sweep(server.port(), spec);
  const json ended = sweep_when_ended(server.port(), id);
  EXPECT_EQ(ended["status"], "stopped") << ended.dump().substr(0, 500);
  EXPECT_EQ(ended["reason"], "disk full");
  EXPECT_EQ(ended["failed"], 0);
  EXPECT_LT(ended["done"].get<int>(), 4000);
  EXPECT_TRUE(ended.contains("report"));  // what was stored is reported
  // a new sweep is refused while the disk is full
  const HttpResult refused = http(server.port(), "POST", "/api/sweeps", dls_grid("more", 2).dump());
  EXPECT_EQ(refused.status, 503) << refused.body;
  // and a stored run can be deleted
  const json page = http(server.port(), "GET", "/api/sweeps/" + std::to_string(id) + "/runs?limit=1").json();
  ASSERT_EQ(page["runs"].size(), 1u) << page.dump();
  const HttpResult removed = http(server.port(), "DELETE", "/api/runs/" + std::to_string(page["runs"][0]["run"].get<std::int64_t>()));
  EXPECT_EQ(removed.status, 200) << removed.body;
  EXPECT_EQ(server.stop(), 0);
}

}  // namespace
}  // namespace rrlab::testing

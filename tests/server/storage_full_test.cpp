// A full disk (serve --test-db-max-pages: PRAGMA max_page_count on the
// server's write connection): the run whose frames no longer fit ends as
// failed with the reason in its summary, new runs get 503 storage_full while
// the condition lasts, reads keep working, and nothing stored before is
// damaged (PRAGMA integrity_check, `rrlab replay --verify`).
#include <rrlab/storage/database.hpp>

#include "server_fixture.hpp"

namespace rrlab::testing {
namespace {

using nlohmann::json;

// 600 pages of 4 KiB: room for the schema and a 500-step run (about 40
// pages), not for a 100000-step one (about 6500 pages); the probe write that
// decides whether the disk is still full needs 256.
const std::vector<std::string> kFullAt = {"--test-db-max-pages", "600"};

HttpResult post(const ServerProcess& server, const std::string& target, const json& body) {
  return http(server.port(), "POST", target, body.dump());
}

json circle_batch(long steps) {
  return {{"scenario", small_scenario("circle", 2000)}, {"mode", "batch"}, {"steps", steps}};
}

json run_of(const ServerProcess& server, std::int64_t id) {
  return http(server.port(), "GET", "/api/runs/" + std::to_string(id)).json();
}

std::string query_text(const std::string& db, const std::string& sql) {
  storage::Database database(db);
  storage::Statement s = database.prepare(sql);
  std::string out;
  while (s.step()) out += (out.empty() ? "" : "; ") + s.column_text(0);
  return out;
}

// What every fault test checks once the server has stopped: the file is
// sound, the run stored before verifies, and the failed run's frames are a
// gap-free prefix counted in its row.
void expect_intact(const std::string& db, std::int64_t earlier, std::int64_t failed) {
  EXPECT_EQ(query_text(db, "PRAGMA integrity_check"), "ok");
  const CommandResult verify = run_rrlab({"replay", std::to_string(earlier), "--db", db, "--verify"});
  EXPECT_EQ(verify.exit_code, 0) << verify.out;
  EXPECT_NE(verify.out.find("\"identical\":true"), std::string::npos) << verify.out;
  const std::string id = std::to_string(failed);
  const std::string frames = query_text(db, "SELECT frames FROM runs WHERE id = " + id);
  EXPECT_EQ(query_text(db, "SELECT COUNT(*) FROM frames WHERE run_id = " + id), frames);
  EXPECT_EQ(query_text(db, "SELECT COALESCE(MAX(seq) + 1, 0) FROM frames WHERE run_id = " + id), frames);
  EXPECT_EQ(query_text(db, "SELECT status FROM runs WHERE id = " + id), "failed");
}

TEST(StorageFull, ABatchRunFailsWithTheReasonNewRunsGet503AndReadsWork) {
  ServerProcess server("", kFullAt);
  const HttpResult earlier = post(server, "/api/runs", circle_batch(500));
  ASSERT_EQ(earlier.status, 200) << earlier.body;
  const std::int64_t earlier_id = earlier.json()["id"];
  ASSERT_EQ(earlier.json()["status"], "completed");

  const HttpResult big = post(server, "/api/runs", circle_batch(100000));
  ASSERT_EQ(big.status, 200) << big.body;
  const std::int64_t failed_id = big.json()["id"];
  EXPECT_EQ(big.json()["status"], "failed");
  const json failed = run_of(server, failed_id);
  EXPECT_EQ(failed["status"], "failed");
  const std::string reason = failed["summary"]["failure"];  // stored in the database
  EXPECT_NE(reason.find("full"), std::string::npos) << reason;
  const long stored = failed["frames"];
  EXPECT_GT(stored, 0);
  EXPECT_LT(stored, 100000);  // about 7000 fit
  EXPECT_EQ(failed["summary"]["frames_stored"], stored);

  // new runs: 503 storage_full with a message, nothing stored
  const std::size_t runs_before = http(server.port(), "GET", "/api/runs").json().size();
  const HttpResult refused = post(server, "/api/runs", circle_batch(10));
  ASSERT_EQ(refused.status, 503) << refused.body;
  EXPECT_EQ(error_of(refused)["code"], "storage_full");
  EXPECT_NE(error_of(refused)["message"].get<std::string>().find("full"), std::string::npos);
  EXPECT_EQ(post(server, "/api/runs", {{"scenario", small_scenario("circle", 5)}}).status, 503);  // live too
  EXPECT_EQ(http(server.port(), "GET", "/api/runs").json().size(), runs_before);

  // reads keep working
  EXPECT_EQ(run_of(server, earlier_id)["frames"], 500);
  const HttpResult frames = http(server.port(), "GET", "/api/runs/" + std::to_string(earlier_id) + "/frames");
  EXPECT_EQ(frames.status, 200);
  EXPECT_EQ(http(server.port(), "GET", "/api/runs/" + std::to_string(failed_id) + "/frames?to=10").status, 200);
  EXPECT_EQ(http(server.port(), "GET", "/api/scenarios").status, 200);

  const std::string db = server.db();
  ASSERT_EQ(server.stop(), 0);
  expect_intact(db, earlier_id, failed_id);
}

TEST(StorageFull, ALiveRunFailsAndDeletingRunsEndsTheCondition) {
  ServerProcess server("", kFullAt);
  const HttpResult earlier = post(server, "/api/runs", circle_batch(500));
  ASSERT_EQ(earlier.status, 200) << earlier.body;
  const std::int64_t earlier_id = earlier.json()["id"];

  // as fast as possible: fills the file within a second
  const HttpResult live = post(server, "/api/runs", {{"scenario", small_scenario("circle", 2000)}, {"rate", 0}});
  ASSERT_EQ(live.status, 201) << live.body;
  const std::int64_t live_id = live.json()["id"];
  json run;
  rrlab::test::eventually([&] { return (run = run_of(server, live_id))["status"] != "running"; },
                          std::chrono::seconds(60), "the live run to end");
  ASSERT_EQ(run["status"], "failed") << run.dump();
  const std::string reason = run["summary"]["failure"];
  EXPECT_NE(reason.find("full"), std::string::npos) << reason;
  EXPECT_EQ(post(server, "/api/runs", circle_batch(10)).status, 503);

  // freeing space (deleting the failed run) ends the condition: a probe write succeeds
  const HttpResult removed = http(server.port(), "DELETE", "/api/runs/" + std::to_string(live_id));
  ASSERT_EQ(removed.status, 200) << removed.body;
  const HttpResult again = post(server, "/api/runs", circle_batch(10));
  ASSERT_EQ(again.status, 200) << again.body;
  EXPECT_EQ(again.json()["status"], "completed");

  const std::string db = server.db();
  ASSERT_EQ(server.stop(), 0);
  EXPECT_EQ(query_text(db, "PRAGMA integrity_check"), "ok");
  const CommandResult verify = run_rrlab({"replay", std::to_string(earlier_id), "--db", db, "--verify"});
  EXPECT_EQ(verify.exit_code, 0) << verify.out;
}

// A database that cannot be written (serve --test-db-read-only: PRAGMA
// query_only on the write connection, as SQLite does for a file it may only
// read): new runs, compares and deletions get 503 storage_readonly with a
// message, reads keep working, and the file is unchanged.
TEST(StorageReadOnly, ChangesGet503AndReadsWork) {
  const std::string dir = temp_dir();
  const std::string db = dir + "/ro.db";
  {
    ServerProcess writer(db);
    ASSERT_EQ(post(writer, "/api/runs", circle_batch(200)).status, 200);
    ASSERT_EQ(writer.stop(), 0);
  }
  const std::string before = query_text(db, "SELECT id || ':' || status || ':' || frames FROM runs");
  ServerProcess server(db, {"--test-db-read-only"});
  const HttpResult refused = post(server, "/api/runs", circle_batch(10));
  ASSERT_EQ(refused.status, 503) << refused.body;
  EXPECT_EQ(error_of(refused)["code"], "storage_readonly");
  EXPECT_NE(error_of(refused)["message"].get<std::string>().find("read"), std::string::npos) << refused.body;
  EXPECT_EQ(post(server, "/api/runs", {{"scenario", small_scenario("circle", 5)}}).status, 503);  // live too
  const HttpResult deleted = http(server.port(), "DELETE", "/api/runs/1");
  EXPECT_EQ(deleted.status, 503) << deleted.body;
  EXPECT_EQ(error_of(deleted)["code"], "storage_readonly");
  const HttpResult resimulated = http(server.port(), "POST", "/api/runs/1/replay", R"({"mode":"resimulate"})");
  EXPECT_EQ(resimulated.status, 503) << resimulated.body;  // re-simulations are refused like new runs
  // reads keep working
  const json runs = http(server.port(), "GET", "/api/runs").json();
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_EQ(run_of(server, 1)["frames"], 200);
  EXPECT_EQ(http(server.port(), "GET", "/api/runs/1/frames?to=10").status, 200);
  const HttpResult replay = http(server.port(), "POST", "/api/runs/1/replay", "{}");
  EXPECT_LT(replay.status, 300) << replay.body;  // playing stored frames writes nothing
  ASSERT_EQ(server.stop(), 0);
  EXPECT_EQ(query_text(db, "SELECT id || ':' || status || ':' || frames FROM runs"), before);
  EXPECT_EQ(query_text(db, "PRAGMA integrity_check"), "ok");
}

}  // namespace
}  // namespace rrlab::testing

// A live run with obstacle moves, weight changes and joystick input is
// re-simulated from its stored events with identical frames; a server killed
// mid-run leaves a sound database.
#include <rrlab/storage/run_store.hpp>

#include "server_fixture.hpp"
#include "support/stored_frames.hpp"

namespace rrlab::testing {
namespace {

using nlohmann::json;

// The ten-million-step runs below only need to be running when the server is
// killed or stopped: raise the per-run quotas that would refuse them (413).
const std::vector<std::string> kLongRuns = {"--max-run-frames", "10000000", "--max-run-bytes", "4000000000"};

class Determinism : public ServerTest {};

TEST_F(Determinism, LiveInputsReSimulateBitForBit) {
  json scenario = small_scenario("joystick", 600);
  scenario["obstacles"].push_back({{"id", "drifter"}, {"shape", "point"}, {"position", {1.5, 1.2}}, {"velocity", {-0.05, 0}}});
  const std::int64_t id = start_live({{"scenario", scenario}, {"rate", 4}});
  const std::string base = "/api/runs/" + std::to_string(id);
  // between two inputs the run takes 40 steps or more, so they land on different steps
  const auto pause = [&] {
    const auto step = [&] { return get(base).json()["live"].value("step", 0L); };
    const long from = step();
    rrlab::test::eventually([&] { return step() >= from + 40; }, std::chrono::seconds(60), "40 more steps");
  };
  pause();
  ASSERT_EQ(send("POST", base + "/joystick", {{"linear", {0.2, 0.1}}}).status, 200);
  pause();
  ASSERT_EQ(send("PUT", base + "/obstacles/ball", {{"position", {0.6, 1.1}}, {"velocity", {0.02, -0.01}}}).status, 200);
  pause();
  ASSERT_EQ(send("PATCH", base + "/params", {{"gain", 6}}).status, 200);
  pause();
  ASSERT_EQ(send("POST", base + "/joystick", {{"linear", {-0.1, 0.2}}}).status, 200);
  pause();
  ASSERT_EQ(send("POST", base + "/method", {{"name", "closest_point"}}).status, 200);
  pause();
  ASSERT_EQ(send("POST", base + "/obstacles", {{"id", "late"}, {"shape", "sphere"}, {"center", {-0.5, 1.0}}, {"radius", 0.1}}).status, 200);
  pause();
  ASSERT_EQ(send("POST", base + "/control", {{"action", "stop"}}).status, 200);
  const json run = wait_ended(id);
  EXPECT_GT(run["frames"].get<long>(), 100);
  EXPECT_EQ(get(base + "/events").json().size(), 6u);

  // the command line re-simulates it from the database, bit for bit
  const CommandResult verify = run_rrlab({"replay", std::to_string(id), "--db", server_->db(), "--verify"});
  EXPECT_EQ(verify.exit_code, 0) << verify.out;
  const json result = json::parse(verify.out);
  EXPECT_TRUE(result["identical"].get<bool>());
  EXPECT_EQ(result["frames_compared"], run["frames"]);

  // and so does the REST replay, into a new stored run
  const HttpResult resim = send("POST", base + "/replay", {{"mode", "resimulate"}});
  ASSERT_EQ(resim.status, 200) << resim.body;
  EXPECT_TRUE(resim.json()["identical"].get<bool>());
  const std::int64_t copy = resim.json()["run"];
  EXPECT_EQ(get("/api/runs/" + std::to_string(copy)).json()["source_run"], id);
}

TEST_F(Determinism, AChangedFrameFailsVerification) {
  const HttpResult batch = send("POST", "/api/runs", {{"scenario", "01_planar7_obstacles"}, {"mode", "batch"}, {"steps", 50}});
  ASSERT_EQ(batch.status, 200);
  const std::int64_t id = batch.json()["id"];
  {
    // tamper with one stored frame: flip the lowest bit of q1 in frame 30
    storage::RunStore store(server_->db());
    std::string data;
    store.frames(id, 30, 30, 1, [&](const storage::StoredFrame& f) {
      data = f.data;
      return false;
    });
    ASSERT_FALSE(data.empty());
    data[24] ^= 1;  // after u32 n, u32 k, i64 step, double t
    rrlab::test::overwrite_frame_data(server_->db(), id, 30, data);
  }
  const CommandResult verify = run_rrlab({"replay", std::to_string(id), "--db", server_->db(), "--verify"});
  EXPECT_EQ(verify.exit_code, 1);
  EXPECT_EQ(json::parse(verify.out)["first_mismatch"], 30);
  EXPECT_EQ(run_rrlab({"replay", "424242", "--db", server_->db()}).exit_code, 2);
}

TEST(CrashSafety, KillDuringABatchRunLeavesASoundDatabase) {
  const std::string dir = temp_dir();
  const std::string db = dir + "/crash.db";
  std::int64_t completed = 0, interrupted = 0;
  long completed_frames = 0;
  {
    ServerProcess server(db, kLongRuns);
    const HttpResult done = http_json(server.port(), "POST", "/api/runs",
                                      {{"scenario", "01_planar7_obstacles"}, {"mode", "batch"}});
    ASSERT_EQ(done.status, 200);
    completed = done.json()["id"];
    completed_frames = done.json()["summary"]["steps"];
    json long_run = small_scenario("circle", 99999);  // ten million steps: still running at the kill
    const HttpResult running = http_json(server.port(), "POST", "/api/runs",
                                         {{"scenario", long_run}, {"mode", "batch"}, {"wait", false}});
    ASSERT_EQ(running.status, 201) << running.body;
    interrupted = running.json()["id"];
    rrlab::test::eventually(  // until some of its frames are committed
        [&] {
          return http(server.port(), "GET", "/api/runs/" + std::to_string(interrupted)).json()["frames"].get<long>() >
                 1000;
        },
        std::chrono::seconds(60), "more than 1000 committed frames before the kill");
    server.kill_hard();
  }
  {
    storage::RunStore store(db);  // opens: WAL recovery
    EXPECT_EQ(store.integrity_check(), "ok");
    EXPECT_EQ(store.run(interrupted)->status, "interrupted");
    EXPECT_EQ(store.run(completed)->status, "completed");
    EXPECT_EQ(store.run(completed)->frames, completed_frames);
  }
  ServerProcess restarted(db);
  EXPECT_EQ(http(restarted.port(), "GET", "/api/runs/" + std::to_string(completed)).json()["status"], "completed");
  const CommandResult verify = run_rrlab({"replay", std::to_string(completed), "--db", db, "--verify"});
  EXPECT_EQ(verify.exit_code, 0) << verify.out;
  std::system(("rm -rf '" + dir + "'").c_str());
}

// kill -9 while a live run is being steered over REST and WebSocket: every
// acknowledged input is stored (events are committed before the answer), the
// frames up to the last committed batch are intact, and the interrupted
// prefix re-simulates bit for bit.
TEST(CrashSafety, KillDuringALiveRunWithInputsKeepsEveryAcknowledgedInput) {
  const std::string dir = temp_dir();
  const std::string db = dir + "/live-crash.db";
  std::int64_t id = 0;
  std::size_t acknowledged = 0;
  {
    ServerProcess server(db);
    const HttpResult started = http_json(server.port(), "POST", "/api/runs",
                                         {{"scenario", small_scenario("joystick", 600)}, {"rate", 4}});
    ASSERT_EQ(started.status, 201) << started.body;
    id = started.json()["id"];
    const std::string base = "/api/runs/" + std::to_string(id);
    WsClient steer(server.port(), "/ws/runs/" + std::to_string(id));
    const auto step = [&] { return http(server.port(), "GET", base).json()["live"].value("step", 0L); };
    for (int i = 0; i < 10; ++i) {
      const double v = 0.02 * (i % 4) - 0.03;
      ASSERT_EQ(http_json(server.port(), "POST", base + "/joystick", {{"linear", {v, 0.02}}}).status, 200);
      ++acknowledged;
      ASSERT_EQ(http_json(server.port(), "PATCH", base + "/params", {{"gain", 3 + i}}).status, 200);
      ++acknowledged;
      steer.send(json{{"type", "input"}, {"kind", "joystick"}, {"payload", {{"linear", {0.01, -v}}}}}.dump());
      ASSERT_TRUE(steer.read_type("ack"));
      ++acknowledged;
      const long from = step();  // the next inputs on later steps
      rrlab::test::eventually([&] { return step() >= from + 10; }, std::chrono::seconds(60), "10 more steps");
    }
    long committed = 0;
    ASSERT_TRUE(rrlab::test::eventually(  // until a few batches of frames are committed
        [&] { return (committed = http(server.port(), "GET", base).json()["frames"].get<long>()) > 500; },
        std::chrono::seconds(60), "more than 500 committed frames before the kill"));
    server.kill_hard();  // the run is still live: its task is 600 s long
  }
  long frames = 0;
  {
    storage::RunStore store(db);
    EXPECT_EQ(store.integrity_check(), "ok");
    EXPECT_EQ(store.run(id)->status, "interrupted");
    EXPECT_EQ(store.events(id).size(), acknowledged);
    frames = store.run(id)->frames;
    EXPECT_GT(frames, 500);
  }
  const CommandResult verify = run_rrlab({"replay", std::to_string(id), "--db", db, "--verify"});
  EXPECT_EQ(verify.exit_code, 0) << verify.out;
  const json report = json::parse(verify.out);
  EXPECT_EQ(report["identical"], true);
  EXPECT_EQ(report["frames_compared"].get<long>(), frames);
  std::system(("rm -rf '" + dir + "'").c_str());
}

TEST(Shutdown, SigtermStopsEverythingAndExitsCleanly) {
  const std::string dir = temp_dir();
  const std::string db = dir + "/shutdown.db";
  std::int64_t live = 0, batch = 0;
  {
    ServerProcess server(db, kLongRuns);
    const HttpResult done = http_json(server.port(), "POST", "/api/runs",
                                      {{"scenario", "01_planar7_obstacles"}, {"mode", "batch"}, {"steps", 100}});
    ASSERT_EQ(done.status, 200);
    live = http_json(server.port(), "POST", "/api/runs", {{"scenario", small_scenario("joystick", 600)}}).json()["id"];
    batch = http_json(server.port(), "POST", "/api/runs",
                      {{"scenario", small_scenario("circle", 99999)}, {"mode", "batch"}, {"wait", false}})
                .json()["id"];
    const std::string stored = std::to_string(done.json()["id"].get<long>());
    ASSERT_EQ(http_json(server.port(), "POST", "/api/runs/" + stored + "/replay", {{"mode", "frames"}}).status, 201);
    WsClient watcher(server.port(), "/ws/runs/" + std::to_string(live));
    ASSERT_TRUE(watcher.read_type("frame"));
    rrlab::test::eventually(  // the batch run has stored frames when SIGTERM comes
        [&] { return http(server.port(), "GET", "/api/runs/" + std::to_string(batch)).json()["frames"].get<long>() > 0; },
        std::chrono::seconds(60), "the batch run's first stored frames");
    EXPECT_EQ(server.stop(), 0);  // SIGTERM: runs stopped, frames flushed, exit 0
  }
  storage::RunStore store(db);
  EXPECT_EQ(store.interrupted_at_open(), 0);
  EXPECT_EQ(store.run(live)->status, "stopped");
  EXPECT_EQ(store.run(batch)->status, "stopped");
  EXPECT_GT(store.run(batch)->frames, 0);
  EXPECT_EQ(store.integrity_check(), "ok");
  std::system(("rm -rf '" + dir + "'").c_str());
}

}  // namespace
}  // namespace rrlab::testing

// RunGroup (server/app/run_group.cpp) on its own, without a server.
#include "app/run_group.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <thread>

#include "scenario/scenario.hpp"
#include "storage/frame_writer.hpp"
#include "storage/run_store.hpp"

namespace rrlab::server {
namespace {

// Found by the ASan build: `rrlab serve` shutting down with a batch run's
// deferred reply pending destroyed the reply's callback (and with it the HTTP
// session) on the run's thread after the run had signalled its exit, when the
// I/O context was already gone (heap-use-after-free). The callbacks are now
// destroyed before wait_exited() returns.
TEST(RunGroupUnit, FinishedCallbacksAreDestroyedBeforeTheRunHasExited) {
  std::string pattern = (std::filesystem::temp_directory_path() / "rrlab-rungroup-XXXXXX").string();
  ASSERT_NE(mkdtemp(pattern.data()), nullptr);
  const std::filesystem::path dir = pattern;
  {
    storage::RunStore store((dir / "runs.db").string());
    storage::FrameWriter writer(store);
    const Scenario scenario = load_scenario_file(std::string(RRLAB_SOURCE_DIR) + "/scenarios/01_planar7_obstacles.json");
    GroupOptions options;
    options.mode = "batch";
    options.rate = 0;
    options.steps = 5;
    auto group = std::make_shared<RunGroup>(RunServices{store, writer}, std::vector<Scenario>{scenario}, options);

    // owned by the callback only; its destructor takes a while, as a session's may
    struct Probe {
      std::atomic<bool>* destroyed;
      ~Probe() {
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
        *destroyed = true;
      }
    };
    std::atomic<bool> destroyed{false}, called{false};
    std::shared_ptr<Probe> probe(new Probe{&destroyed});
    group->when_finished([probe, &called] { called = true; });
    probe.reset();
    group->start();
    group->wait_exited();
    EXPECT_TRUE(called);
    EXPECT_TRUE(destroyed);  // false before the fix: destroyed after wait_exited() returned
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace rrlab::server

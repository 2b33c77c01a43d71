// RunGroup (server/app/run_group.cpp) on its own, without a server.
#include "app/run_group.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <future>
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


// Waits (bounded, however slow the machine) for a completion to settle.
storage::Outcome settled(const std::shared_ptr<storage::Completion>& done) {
  auto promise = std::make_shared<std::promise<storage::Outcome>>();
  auto future = promise->get_future();
  done->then([promise](const storage::Outcome& o) { promise->set_value(o); });
  EXPECT_EQ(future.wait_for(std::chrono::seconds(60)), std::future_status::ready);
  return future.get();
}

// An input is applied at once and answered once its event is stored; a
// single step is answered once it is taken: nobody waits in between.
TEST(RunGroupUnit, InputsSettleOnceStoredAndStepsOnceTaken) {
  std::string pattern = (std::filesystem::temp_directory_path() / "rrlab-rungroup-XXXXXX").string();
  ASSERT_NE(mkdtemp(pattern.data()), nullptr);
  const std::filesystem::path dir = pattern;
  {
    storage::RunStore store((dir / "runs.db").string());
    storage::FrameWriter writer(store);
    const Scenario scenario = load_scenario_file(std::string(RRLAB_SOURCE_DIR) + "/scenarios/01_planar7_obstacles.json");
    GroupOptions options;
    options.paused = true;
    auto group = std::make_shared<RunGroup>(RunServices{store, writer}, std::vector<Scenario>{scenario}, options);
    group->start();
    const std::int64_t run = group->run_id(0);

    Accepted input = group->input(0, "params", {{"gain", 3}}, "");
    ASSERT_TRUE(input.pending);
    EXPECT_EQ(input.status["params"]["gain"], 3);  // applied before it is stored
    EXPECT_TRUE(settled(input.pending).ok());
    ASSERT_EQ(store.events(run).size(), 1u);  // stored before the answer
    EXPECT_EQ(store.events(run)[0].seq, 0);   // takes effect in the first step

    Accepted step = group->control(0, {{"action", "step"}});
    ASSERT_TRUE(step.pending);
    const storage::Outcome stepped = settled(step.pending);
    EXPECT_TRUE(stepped.ok());
    EXPECT_EQ(stepped.result["frames"], 1);  // the status after the step
    EXPECT_EQ(step.status["frames"], 0);     // the status when it was asked

    // steps asked for at once settle in turn, each with its own status
    std::vector<std::shared_ptr<storage::Completion>> steps;
    for (int i = 0; i < 5; ++i) steps.push_back(group->control(0, {{"action", "step"}}).pending);
    for (int i = 0; i < 5; ++i) EXPECT_EQ(settled(steps[size_t(i)]).result["frames"], 2 + i);

    group->request_stop();
    group->wait_exited();
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace rrlab::server

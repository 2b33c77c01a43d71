// RunGroup (server/app/run_group.cpp) on its own, without a server.
#include <rrlab/server/app/run_group.hpp>

#include <gtest/gtest.h>
#include <stdlib.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <future>
#include <thread>

#include <rrlab/scenario/scenario.hpp>
#include <rrlab/storage/frame_writer.hpp>
#include <rrlab/storage/run_store.hpp>

namespace rrlab::server {
namespace {

// A store and frame writer in a temporary folder, and the demo scenario.
class RunGroupUnit : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (std::filesystem::temp_directory_path() / "rrlab-rungroup-XXXXXX").string();
    ASSERT_NE(mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
    store_ = std::make_unique<storage::RunStore>((dir_ / "runs.db").string());
    writer_ = std::make_unique<storage::FrameWriter>(*store_);
  }
  void TearDown() override {
    writer_.reset();
    store_.reset();
    std::filesystem::remove_all(dir_);
  }
  std::shared_ptr<RunGroup> group(const GroupOptions& options) {
    const Scenario scenario = load_scenario_file(std::string(RRLAB_SOURCE_DIR) + "/scenarios/01_planar7_obstacles.json");
    return std::make_shared<RunGroup>(RunServices{*store_, *writer_}, std::vector<Scenario>{scenario}, options);
  }
  std::filesystem::path dir_;
  std::unique_ptr<storage::RunStore> store_;
  std::unique_ptr<storage::FrameWriter> writer_;
};

// Found by the ASan build: `rrlab serve` shutting down with a batch run's
// deferred reply pending destroyed the reply's callback (and with it the HTTP
// session) on the run's thread after the run had signalled its exit, when the
// I/O context was already gone (heap-use-after-free). The callbacks are now
// destroyed before wait_exited() returns.
TEST_F(RunGroupUnit, FinishedCallbacksAreDestroyedBeforeTheRunHasExited) {
  {
    GroupOptions options;
    options.mode = RunMode::batch;
    options.rate = 0;
    options.steps = 5;
    auto group = this->group(options);

    // owned by the callback only; its destructor takes a while, as a session's may
    struct Probe {
      std::atomic<bool>* destroyed;
      ~Probe() {
        // about time itself: a slow destructor, which a wait_exited() that did not wait for it would outrun
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
TEST_F(RunGroupUnit, InputsSettleOnceStoredAndStepsOnceTaken) {
  {
    GroupOptions options;
    options.paused = true;
    auto group = this->group(options);
    group->start();
    const std::int64_t run = group->run_id(0);

    Accepted input = group->input(0, InputKind::params, {{"gain", 3}});
    ASSERT_TRUE(input.pending);
    EXPECT_EQ(input.status["params"]["gain"], 3);  // applied before it is stored
    EXPECT_TRUE(settled(input.pending).ok());
    ASSERT_EQ(store_->events(run).size(), 1u);  // stored before the answer
    EXPECT_EQ(store_->events(run)[0].seq, 0);   // takes effect in the first step

    Accepted step = group->control(0, {ControlAction::step, std::nullopt});
    ASSERT_TRUE(step.pending);
    const storage::Outcome stepped = settled(step.pending);
    EXPECT_TRUE(stepped.ok());
    EXPECT_EQ(stepped.result["frames"], 1);  // the status after the step
    EXPECT_EQ(step.status["frames"], 0);     // the status when it was asked

    // steps asked for at once settle in turn, each with its own status
    std::vector<std::shared_ptr<storage::Completion>> steps;
    for (int i = 0; i < 5; ++i) steps.push_back(group->control(0, {ControlAction::step, std::nullopt}).pending);
    for (int i = 0; i < 5; ++i) EXPECT_EQ(settled(steps[size_t(i)]).result["frames"], 2 + i);

    group->request_stop();
    group->wait_exited();
  }
}

}  // namespace
}  // namespace rrlab::server

// The runner: jobs do not change results, shards merged equal the whole,
// stored keys are skipped (resume), a stop request stops.
#include <gtest/gtest.h>

#include <thread>

#include <rrlab/sweep/sweep_merge.hpp>
#include <rrlab/sweep/sweep_runner.hpp>

#include "sweep_test_support.hpp"

namespace rrlab::sweep {
namespace {

using testing::parse_spec;
using testing::small_spec;
using testing::stored_runs;

RunnerOutcome run_all(const SweepSpec& spec, const std::vector<SweepCase>& cases, storage::RunStore& store, int jobs,
                      bool frames = false) {
  RunnerOptions options;
  options.jobs = jobs;
  options.frames = frames;
  return run_sweep(spec, cases, store, options);
}

TEST(SweepRunner, OneJobAndTwoJobsStoreIdenticalRuns) {
  testing::TempDir dir;
  const SweepSpec spec = parse_spec(small_spec());
  const std::vector<SweepCase> cases = expand_sweep(spec);
  storage::RunStore one(dir.file("one.db")), two(dir.file("two.db"));
  const RunnerOutcome a = run_all(spec, cases, one, 1), b = run_all(spec, cases, two, 2);
  EXPECT_EQ(a.stored, cases.size());
  EXPECT_EQ(b.stored, cases.size());
  EXPECT_TRUE(a.failures.empty()) << a.failures.front();
  EXPECT_FALSE(a.interrupted);
  const auto runs_one = stored_runs(one, "small"), runs_two = stored_runs(two, "small");
  ASSERT_EQ(runs_one.size(), cases.size());
  EXPECT_EQ(runs_one, runs_two);
  // the record as run: the case's seed and method configuration in the scenario JSON
  const nlohmann::json& dls = runs_one.at("small/file:01_planar7_obstacles/dls{lambda=0.02}/2");
  const nlohmann::json scenario = nlohmann::json::parse(dls["scenario"].get<std::string>());
  EXPECT_EQ(scenario["seed"], 2);
  EXPECT_EQ(scenario["method"]["name"], "dls");
  EXPECT_EQ(scenario["method"]["params"]["lambda"], 0.02);
  EXPECT_EQ(dls["summary"]["steps"], 60);
  EXPECT_EQ(nlohmann::json::parse(dls["params"].get<std::string>())["lambda"], 0.02);
  EXPECT_EQ(one.run(one.sweep_runs("small").front().run_id)->frames, 0);  // no frames by default
}

TEST(SweepRunner, FramesOnRequestInTheSameRun) {
  testing::TempDir dir;
  const SweepSpec spec = parse_spec(small_spec());
  const std::vector<SweepCase> cases = cases_of_shard(expand_sweep(spec), {0, 6});
  storage::RunStore store(dir.file("frames.db"));
  run_all(spec, cases, store, 2, true);
  for (const storage::SweepRunEntry& e : store.sweep_runs("small")) EXPECT_EQ(store.run(e.run_id)->frames, 60);
}

TEST(SweepRunner, FourShardsMergedEqualTheWholeSweep) {
  testing::TempDir dir;
  const SweepSpec spec = parse_spec(small_spec());
  const std::vector<SweepCase> all = expand_sweep(spec);
  storage::RunStore whole(dir.file("whole.db"));
  run_all(spec, all, whole, 2);
  storage::RunStore merged(dir.file("merged.db"));
  for (int i = 0; i < 4; ++i) {
    storage::RunStore shard(dir.file("shard" + std::to_string(i) + ".db"));
    const RunnerOutcome outcome = run_all(spec, cases_of_shard(all, {i, 4}), shard, 1);
    EXPECT_EQ(outcome.stored, all.size() / 4);
    const MergeOutcome m = merge_sweep_runs(merged, shard);
    EXPECT_EQ(m.copied, all.size() / 4);
  }
  EXPECT_EQ(stored_runs(merged, "small"), stored_runs(whole, "small"));
}

TEST(SweepRunner, ResumeSkipsStoredKeys) {
  testing::TempDir dir;
  const SweepSpec spec = parse_spec(small_spec());
  const std::vector<SweepCase> all = expand_sweep(spec);
  storage::RunStore store(dir.file("resume.db"));
  const RunnerOutcome first = run_all(spec, cases_of_shard(all, {1, 3}), store, 2);
  EXPECT_EQ(first.stored, 4u);
  const RunnerOutcome second = run_all(spec, all, store, 2);
  EXPECT_EQ(second.already_stored, 4u);
  EXPECT_EQ(second.stored, all.size() - 4);
  const RunnerOutcome third = run_all(spec, all, store, 2);
  EXPECT_EQ(third.stored, 0u);
  EXPECT_EQ(store.sweep_keys("small").size(), all.size());
  EXPECT_EQ(store.runs({.limit = 1000}).size(), all.size());  // no run stored twice
}

TEST(SweepRunner, AStopRequestStartsNoRun) {
  testing::TempDir dir;
  const SweepSpec spec = parse_spec(small_spec());
  storage::RunStore store(dir.file("stop.db"));
  std::atomic<bool> stop{true};
  RunnerOptions options;
  options.stop = &stop;
  const RunnerOutcome outcome = run_sweep(spec, expand_sweep(spec), store, options);
  EXPECT_TRUE(outcome.interrupted);
  EXPECT_EQ(outcome.stored, 0u);
}

// A stop ends the run in progress between two steps: before, a worker
// finished its run first (16 s for a 5e6-step run; a server with 1e7-step
// sweep runs went on 60 s after SIGTERM). One case of 1e7 steps (minutes)
// ends unstored and uncounted as a failure once stop is set. The stop may
// come before the run starts (then this is AStopRequestStartsNoRun again);
// Simulator.RunToEndStopsBetweenSteps checks the step-level stop exactly.
TEST(SweepRunner, AStopEndsTheRunInProgress) {
  testing::TempDir dir;
  nlohmann::json doc = small_spec("long");
  doc["scenarios"] = {"01_planar7_obstacles"};
  doc["methods"] = {"dls"};
  doc["seeds"] = {1};
  doc["steps"] = 10'000'000;
  const SweepSpec spec = parse_spec(doc);
  storage::RunStore store(dir.file("long.db"));
  std::atomic<bool> stop{false};
  RunnerOptions options;
  options.stop = &stop;
  RunnerOutcome outcome;
  std::thread sweep([&] { outcome = run_sweep(spec, expand_sweep(spec), store, options); });
  stop = true;
  sweep.join();
  EXPECT_TRUE(outcome.interrupted);
  EXPECT_EQ(outcome.stored, 0u);
  EXPECT_TRUE(outcome.failures.empty()) << outcome.failures.front();
}

TEST(SweepRunner, AddSweepRunStoresAKeyOnce) {
  testing::TempDir dir;
  storage::RunStore store(dir.file("once.db"));
  storage::FinishedRun run;
  run.run = {"s", "{}", "pinv", "{}", "batch", 1, 7, "[]", std::nullopt, std::nullopt};
  run.summary_json = "{}";
  const storage::SweepRunRow row{"w", "w/file:s/pinv/own", "file:s", "pinv", "file", true};
  EXPECT_TRUE(store.add_sweep_run(run, row));
  EXPECT_FALSE(store.add_sweep_run(run, row));
  EXPECT_EQ(store.runs({}).size(), 1u);
  EXPECT_EQ(store.run(store.sweep_runs("w").front().run_id)->status, "completed");
  // deleting the run removes its sweep row too
  EXPECT_TRUE(store.delete_run(store.sweep_runs("w").front().run_id));
  EXPECT_TRUE(store.sweep_keys("w").empty());
}

}  // namespace
}  // namespace rrlab::sweep

namespace rrlab::sweep {
namespace {

// A failed run is stored with its first failure mode and time; a passed one
// with none; generated cases with their witness's difficulty, and the witness
// lane passes them all.
TEST(SweepRunner, FailedRunsStoreTheirFirstFailureAndCasesTheirDifficulty) {
  testing::TempDir dir;
  const SweepSpec spec = parse_spec(nlohmann::json::parse(R"({
    "name": "modes",
    "scenarios": [{"generator": "planar_clutter", "count": 3, "seed": 5}],
    "methods": ["pinv", "witness"],
    "success": {"max_tracking_error": 0.01, "collision": false, "joint_limits": true}})"));
  const std::vector<SweepCase> cases = expand_sweep(spec);
  storage::RunStore store(dir.file("modes.db"));
  EXPECT_EQ(run_all(spec, cases, store, 2).stored, 6u);
  for (const storage::SweepRunEntry& e : store.sweep_runs("modes")) {
    ASSERT_TRUE(e.difficulty_json) << e.row.key;
    EXPECT_TRUE(nlohmann::json::parse(*e.difficulty_json).contains("clearance"));
    if (e.row.config_key == "witness") {
      EXPECT_TRUE(e.row.success) << e.row.key;
      EXPECT_FALSE(e.row.failure_mode);
    } else {  // block_pinv: pinv runs into the first obstacle
      EXPECT_FALSE(e.row.success) << e.row.key;
      EXPECT_EQ(e.row.failure_mode, "collision") << e.row.key;
      ASSERT_TRUE(e.row.failure_t);
      EXPECT_GT(*e.row.failure_t, 0);
    }
  }
}

}  // namespace
}  // namespace rrlab::sweep

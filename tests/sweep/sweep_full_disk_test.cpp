// A sweep on a disk that is really full (a tmpfs of a few MiB): the first run
// that cannot be stored stops the sweep, with the reason, instead of every
// later run being computed and failing in turn; what was stored stays and a
// resumed sweep goes on from there once runs are deleted.
#include <gtest/gtest.h>

#include "storage/database.hpp"
#include "storage/disk_reserve.hpp"
#include "support/small_disk.hpp"
#include "sweep/sweep_runner.hpp"
#include "sweep_test_support.hpp"

namespace rrlab::sweep {
namespace {

using testing::parse_spec;

// Many short runs, with frames: each stores a few hundred KB.
nlohmann::json disk_filling_spec() {
  nlohmann::json spec = testing::small_spec("filling");
  spec["methods"] = nlohmann::json::parse(R"(["pinv", {"name": "dls", "params": {"lambda": [0.01, 0.02, 0.05, 0.1, 0.2]}}])");
  spec["seeds"] = nlohmann::json::array();
  for (int seed = 1; seed <= 40; ++seed) spec["seeds"].push_back(seed);
  spec["steps"] = 200;
  return spec;
}

TEST(SweepFullDisk, TheFirstRunThatCannotBeStoredStopsTheSweepAndDeletesStillWork) {
  test::SmallDisk disk(24);
  ASSERT_EQ(disk.error(), "") << "a tmpfs in a private mount namespace is needed for this test";
  storage::RunStore store(disk.path("sweep.db"), storage::DiskReserve::kDefaultBytes);  // as the server opens it
  const SweepSpec spec = parse_spec(disk_filling_spec());
  const std::vector<SweepCase> cases = expand_sweep(spec);  // 2 x 6 x 40 = 480 runs, far more than fit
  RunnerOptions options;
  options.jobs = 2;
  options.frames = true;
  const RunnerOutcome outcome = run_sweep(spec, cases, store, options);

  EXPECT_EQ(outcome.storage_stopped, "disk full");
  EXPECT_TRUE(outcome.interrupted);
  EXPECT_TRUE(outcome.failures.empty()) << outcome.failures.front();  // no run failed: the sweep stopped
  EXPECT_GT(outcome.stored, 0u);
  EXPECT_LT(outcome.stored, cases.size());
  // stopped at once: at most one run in flight per job was computed after the first refusal
  const std::vector<storage::SweepRunEntry> runs = store.sweep_runs("filling");
  EXPECT_EQ(runs.size(), outcome.stored);

  // the remedy works on the full disk: delete runs, then resume
  ASSERT_TRUE(store.delete_run(runs.front().run_id));
  ASSERT_TRUE(store.delete_run(runs.back().run_id));
  EXPECT_EQ(store.integrity_check(), "ok");
}

TEST(SweepFullDisk, ASweepOnADiskAlreadyFullStopsAtItsFirstRun) {
  test::SmallDisk disk(16);
  ASSERT_EQ(disk.error(), "") << "a tmpfs in a private mount namespace is needed for this test";
  storage::RunStore store(disk.path("sweep.db"), storage::DiskReserve::kDefaultBytes);
  test::fill_with_a_file(disk.path("other-data"));
  const SweepSpec spec = parse_spec(disk_filling_spec());
  RunnerOptions options;
  options.jobs = 2;
  options.frames = true;
  const RunnerOutcome outcome = run_sweep(spec, expand_sweep(spec), store, options);
  EXPECT_EQ(outcome.storage_stopped, "disk full");
  EXPECT_EQ(outcome.stored, 0u);
  EXPECT_TRUE(outcome.failures.empty());
}

}  // namespace
}  // namespace rrlab::sweep

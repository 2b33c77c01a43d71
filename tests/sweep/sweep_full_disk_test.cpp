// A sweep on a disk that is really full (a tmpfs of a few MiB): the first run
// that cannot be stored stops the sweep, with the reason, instead of every
// later run being computed and failing in turn; what was stored stays and a
// resumed sweep goes on from there once runs are deleted.
#include <gtest/gtest.h>

#include <rrlab/storage/database.hpp>
#include <rrlab/storage/disk_reserve.hpp>
#include <rrlab/sweep/sweep_runner.hpp>

#include "support/small_disk.hpp"
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
  const std::string db = disk.path("sweep.db");
  std::vector<std::int64_t> stored_ids;
  {
    storage::RunStore store(db, storage::DiskReserve::kDefaultBytes);  // as the server opens it
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
    const std::vector<storage::SweepRunEntry> runs = store.sweep_runs("filling");
    EXPECT_EQ(runs.size(), outcome.stored);
    for (const storage::SweepRunEntry& e : runs) stored_ids.push_back(e.run_id);
  }
  ASSERT_GE(stored_ids.size(), 3u);
  // a restart on the disk the sweep filled: opening takes what its journal
  // needs of the reserve, the deletes what they need of the rest
  storage::RunStore store(db, storage::DiskReserve::kDefaultBytes);
  for (size_t i = 0; i < 3; ++i) ASSERT_TRUE(store.delete_run(stored_ids[i])) << "delete " << i << " after the restart";
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

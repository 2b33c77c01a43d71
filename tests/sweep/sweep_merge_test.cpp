// Merging is idempotent: the (sweep, key) of a run decides.
#include <gtest/gtest.h>

#include <rrlab/sweep/sweep_merge.hpp>
#include <rrlab/sweep/sweep_runner.hpp>

#include "sweep_test_support.hpp"

namespace rrlab::sweep {
namespace {

TEST(SweepMerge, TwiceOrOverlappingAddsNothingTwice) {
  testing::TempDir dir;
  const SweepSpec spec = testing::parse_spec(testing::small_spec());
  const std::vector<SweepCase> all = expand_sweep(spec);
  storage::RunStore a(dir.file("a.db")), b(dir.file("b.db")), out(dir.file("out.db"));
  RunnerOptions options;
  options.jobs = 2;
  options.frames = true;
  run_sweep(spec, cases_of_shard(all, {0, 2}), a, options);
  run_sweep(spec, all, b, options);  // overlaps a entirely

  EXPECT_EQ(merge_sweep_runs(out, a).copied, all.size() / 2);
  const MergeOutcome again = merge_sweep_runs(out, a);
  EXPECT_EQ(again.copied, 0u);
  EXPECT_EQ(again.already_present, all.size() / 2);
  const MergeOutcome overlap = merge_sweep_runs(out, b);
  EXPECT_EQ(overlap.copied, all.size() / 2);
  EXPECT_EQ(overlap.already_present, all.size() / 2);

  EXPECT_EQ(out.sweep_keys("small").size(), all.size());
  EXPECT_EQ(out.runs({.limit = 1000}).size(), all.size());
  EXPECT_EQ(testing::stored_runs(out, "small"), testing::stored_runs(b, "small"));
  // frames came along
  for (const storage::SweepRunEntry& e : out.sweep_runs("small")) EXPECT_EQ(out.run(e.run_id)->frames, 60);
  EXPECT_EQ(out.integrity_check(), "ok");
}

}  // namespace
}  // namespace rrlab::sweep

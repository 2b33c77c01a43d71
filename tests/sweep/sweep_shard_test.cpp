// Shard selection: --shard I/N, Slurm array and Kubernetes indexed jobs.
#include <gtest/gtest.h>

#include <map>

#include <rrlab/scenario/scenario.hpp>
#include <rrlab/sweep/sweep_shard.hpp>

namespace rrlab::sweep {
namespace {

EnvLookup env_of(std::map<std::string, std::string> vars) {
  return [vars = std::move(vars)](const char* name) -> const char* {
    const auto it = vars.find(name);
    return it == vars.end() ? nullptr : it->second.c_str();
  };
}

void expect_error(const std::function<void()>& f, const std::string& prefix) {
  try {
    f();
    ADD_FAILURE() << "no error, expected " << prefix;
  } catch (const ScenarioError& e) {
    EXPECT_EQ(std::string(e.what()).substr(0, prefix.size()), prefix) << e.what();
  }
}

TEST(SweepShard, FlagWins) {
  const Shard s = resolve_shard("1/4", std::nullopt, env_of({{"SLURM_ARRAY_TASK_ID", "3"}}));
  EXPECT_EQ(s.index, 1);
  EXPECT_EQ(s.count, 4);
  EXPECT_TRUE(s.contains(5));
  EXPECT_FALSE(s.contains(4));
}

TEST(SweepShard, WholeSweepWithoutFlagsOrEnvironment) {
  const Shard s = resolve_shard(std::nullopt, std::nullopt, env_of({}));
  EXPECT_EQ(s.index, 0);
  EXPECT_EQ(s.count, 1);
}

TEST(SweepShard, SlurmArray) {
  Shard s = resolve_shard(std::nullopt, std::nullopt,
                          env_of({{"SLURM_ARRAY_TASK_ID", "2"}, {"SLURM_ARRAY_TASK_COUNT", "5"}}));
  EXPECT_EQ(s.index, 2);
  EXPECT_EQ(s.count, 5);
  s = resolve_shard(std::nullopt, 3, env_of({{"SLURM_ARRAY_TASK_ID", "11"}, {"SLURM_ARRAY_TASK_MIN", "10"}}));
  EXPECT_EQ(s.index, 1);
  EXPECT_EQ(s.count, 3);
}

TEST(SweepShard, KubernetesIndexedJob) {
  const Shard s = resolve_shard(std::nullopt, 8, env_of({{"JOB_COMPLETION_INDEX", "7"}}));
  EXPECT_EQ(s.index, 7);
  EXPECT_EQ(s.count, 8);
}

TEST(SweepShard, BadInputIsNamed) {
  expect_error([] { parse_shard("4/4", "--shard"); }, "--shard: the shard index must be in [0, 3], got 4");
  expect_error([] { parse_shard("1-4", "--shard"); }, "--shard: must be I/N");
  expect_error([] { parse_shard("0/0", "--shard"); }, "--shard: the shard count must be in");
  expect_error([] { resolve_shard("0/2", 2, env_of({})); }, "--shards: give --shard I/N or --shards N, not both");
  expect_error([] { resolve_shard(std::nullopt, 2, env_of({})); }, "--shards: needs SLURM_ARRAY_TASK_ID");
  expect_error([] { resolve_shard(std::nullopt, std::nullopt, env_of({{"JOB_COMPLETION_INDEX", "1"}})); },
               "--shards: JOB_COMPLETION_INDEX is set");
  expect_error([] { resolve_shard(std::nullopt, std::nullopt, env_of({{"SLURM_ARRAY_TASK_ID", "x"}, {"SLURM_ARRAY_TASK_COUNT", "2"}})); },
               "SLURM_ARRAY_TASK_ID: must be a non-negative integer");
  expect_error([] { resolve_shard(std::nullopt, 2, env_of({{"JOB_COMPLETION_INDEX", "2"}})); },
               "--shards: the shard index must be in [0, 1]");
}

}  // namespace
}  // namespace rrlab::sweep

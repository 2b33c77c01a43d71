// Which shard this process runs: --shard I/N, else an array job's index
// (Slurm: SLURM_ARRAY_TASK_ID minus SLURM_ARRAY_TASK_MIN, of
// SLURM_ARRAY_TASK_COUNT or --shards N; Kubernetes indexed jobs:
// JOB_COMPLETION_INDEX with --shards N), else the whole sweep (0/1).
#pragma once

#include <functional>
#include <optional>
#include <string>

#include <rrlab/sweep/sweep_expansion.hpp>

namespace rrlab::sweep {

using EnvLookup = std::function<const char*(const char*)>;

// Throws ScenarioError naming the option or variable that is wrong.
Shard parse_shard(const std::string& text, const std::string& what);  // "I/N"
Shard resolve_shard(const std::optional<std::string>& shard, const std::optional<int>& shards, const EnvLookup& env);

}  // namespace rrlab::sweep

#include <rrlab/sweep/sweep_shard.hpp>

#include <charconv>

#include <rrlab/scenario/scenario.hpp>

namespace rrlab::sweep {

namespace {

constexpr long kMaxShards = 1'000'000;

std::optional<long> integer(const std::string& text) {
  long value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

long env_integer(const EnvLookup& env, const char* name) {
  const char* text = env(name);
  const std::optional<long> value = text ? integer(text) : std::nullopt;
  if (!value || *value < 0) throw ScenarioError(name, std::string("must be a non-negative integer, got \"") + (text ? text : "") + "\"");
  return *value;
}

Shard checked(long index, long count, const std::string& what) {
  if (count < 1 || count > kMaxShards)
    throw ScenarioError(what, "the shard count must be in [1, " + std::to_string(kMaxShards) + "], got " + std::to_string(count));
  if (index < 0 || index >= count)
    throw ScenarioError(what, "the shard index must be in [0, " + std::to_string(count - 1) + "], got " + std::to_string(index));
  return {int(index), int(count)};
}

}  // namespace

Shard parse_shard(const std::string& text, const std::string& what) {
  const auto slash = text.find('/');
  const std::optional<long> index = slash == std::string::npos ? std::nullopt : integer(text.substr(0, slash));
  const std::optional<long> count = slash == std::string::npos ? std::nullopt : integer(text.substr(slash + 1));
  if (!index || !count) throw ScenarioError(what, "must be I/N (shard I of N, 0-based), got \"" + text + "\"");
  return checked(*index, *count, what);
}

Shard resolve_shard(const std::optional<std::string>& shard, const std::optional<int>& shards, const EnvLookup& env) {
  if (shard) {
    if (shards) throw ScenarioError("--shards", "give --shard I/N or --shards N, not both");
    return parse_shard(*shard, "--shard");
  }
  if (env("SLURM_ARRAY_TASK_ID")) {
    long index = env_integer(env, "SLURM_ARRAY_TASK_ID");
    if (env("SLURM_ARRAY_TASK_MIN")) index -= env_integer(env, "SLURM_ARRAY_TASK_MIN");
    const long count = shards ? *shards : env("SLURM_ARRAY_TASK_COUNT") ? env_integer(env, "SLURM_ARRAY_TASK_COUNT") : -1;
    if (count < 0) throw ScenarioError("--shards", "SLURM_ARRAY_TASK_ID is set without SLURM_ARRAY_TASK_COUNT: give --shards N");
    return checked(index, count, shards ? "--shards" : "SLURM_ARRAY_TASK_COUNT");
  }
  if (env("JOB_COMPLETION_INDEX")) {
    if (!shards) throw ScenarioError("--shards", "JOB_COMPLETION_INDEX is set: give the job's completions as --shards N");
    return checked(env_integer(env, "JOB_COMPLETION_INDEX"), *shards, "--shards");
  }
  if (shards) throw ScenarioError("--shards", "needs SLURM_ARRAY_TASK_ID or JOB_COMPLETION_INDEX in the environment (or use --shard I/N)");
  return {0, 1};
}

}  // namespace rrlab::sweep

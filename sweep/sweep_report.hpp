// What a sweep report says, computed from stored sweep runs (no spec needed:
// success was judged when each run was stored).
//  - per sweep × method configuration × family (generator family or "file"):
//    n, success rate with its 95 % Wilson interval, median and 10th
//    percentile of min distance (over runs with a finite one: runs without
//    obstacles have none), median of max tracking error, share of runs with a
//    joint-limit violation, share with non-finite steps, and step time: the
//    median over runs of each run's step_us.p50, and of each run's step_us.p99;
//  - paired comparisons of every two configurations of a sweep on the same
//    cases (same scenario key and seed): wins/losses/ties on success, and on
//    min distance (larger wins; within 1e-9 is a tie);
//  - a ranking of each sweep's configurations by success rate, then median
//    max tracking error.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "storage/run_store.hpp"
#include "sweep/sweep_stats.hpp"

namespace rrlab::sweep {

struct GroupStats {
  std::string sweep, config_key, family;
  size_t n = 0, successes = 0;
  double success_rate = 0;
  Interval success_interval;
  double median_min_distance = 0, p10_min_distance = 0;  // NaN: no run with a finite one
  double median_max_tracking_error = 0;
  double joint_limit_share = 0, nonfinite_share = 0;
  double step_us_p50 = 0, step_us_p99 = 0;  // medians over runs of each run's p50 / p99
};

struct WinLossTie {
  size_t wins = 0, losses = 0, ties = 0;
};

struct PairedComparison {
  std::string sweep, a, b;  // configuration keys; wins are a's
  size_t cases = 0;
  WinLossTie success, min_distance;
};

struct RankEntry {
  std::string sweep, config_key;
  size_t n = 0;
  double success_rate = 0, median_max_tracking_error = 0;
};

struct SweepReport {
  std::vector<std::string> sweeps;
  std::vector<GroupStats> groups;       // by sweep, configuration, family
  std::vector<PairedComparison> pairs;  // by sweep, then a, b
  std::vector<RankEntry> ranking;       // by sweep, best first
};

inline constexpr double kDistanceTie = 1e-9;

// Throws std::runtime_error on a stored summary that is not JSON.
SweepReport build_report(const std::vector<storage::SweepRunEntry>& runs);

}  // namespace rrlab::sweep

// What a sweep report says, computed from stored sweep runs (no spec needed:
// success was judged when each run was stored).
//  - per sweep × method configuration × family (generator family or "file"):
//    n, success rate with its 95 % Wilson interval, median and 10th
//    percentile of min distance (over runs with a finite one: runs without
//    obstacles have none), median of max tracking error, share of runs with a
//    joint-limit violation, share with non-finite steps, and step time: the
//    median over runs of each run's step_us.p50, and of each run's step_us.p99;
//    smoothness: the median over runs of each run's RMS joint jerk (rms_jerk);
//  - paired comparisons of every two configurations of a sweep on the same
//    cases (same scenario key and seed): wins/losses/ties on success, and on
//    min distance (larger wins; within 1e-9 is a tie); only for a sweep of at
//    most kMaxPairedConfigs configurations (their number grows with the
//    square: a larger sweep has each configuration against pinv and its
//    family's best instead, below);
//  - a ranking of each sweep's configurations by success rate, then median
//    max tracking error;
//  - per group also the failed runs' first failure modes (collision,
//    joint_limit, joint_speed, tracking_lost, stalled, nonfinite; "unrecorded" for runs
//    stored before modes were) and the step time as a ratio to pinv's on the
//    same family (shifted geometric means of the runs' step_us.p50, shift 1 µs);
//  - per sweep × family, each configuration paired with pinv and with the
//    family's best (highest success rate, then lowest median max tracking
//    error) on the same cases: success wins/losses/ties and the exact McNemar
//    p-value;
//  - "which method when": per sweep × family, the configurations whose
//    success is not significantly below the best's (not: fewer wins than
//    losses against it with p < 0.05) and that succeed at least once, best
//    first, with their step time, and the smallest difference the family's
//    cases detect (sweep_power.hpp); past kSeparableDifference no
//    configurations are listed: the cases are too few to separate them;
//  - what to try when the first choice fails: per sweep × family, the best
//    first choice with a fallback and the cases no configuration solves
//    (sweep_fallback.hpp);
//  - success against difficulty per group: the family's cases binned at the
//    quartiles of the witness's clearance (or limit margin), and by the
//    obstacles the minimum-norm arm meets and those tight on the witness
//    (integer bins 0, 1, 2, 3, 4+).
#pragma once

#include <array>
#include <atomic>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <rrlab/storage/run_store.hpp>
#include <rrlab/sweep/sweep_fallback.hpp>
#include <rrlab/sweep/sweep_stats.hpp>

namespace rrlab::sweep {

// One bin of success against difficulty: the runs whose case's difficulty
// measure lies in [low, high].
struct DifficultyBin {
  double low = 0, high = 0;
  size_t n = 0, successes = 0;
};

// Success against an obstacle count of the case, the witness.difficulty
// measures below: bin k holds the cases with k obstacles, the last those with
// kCountBins - 1 or more (low = k, high = k; the last's high is +inf).
inline constexpr size_t kCountBins = 5;
// blocking: distinct obstacles the minimum-norm (pinv) arm meets over the run;
// tight: obstacles within twice the family's clearance of the witness arm.
inline constexpr std::array<const char*, 2> kCountMeasures = {"blocking_obstacles", "tight_obstacles"};

struct CountDifficulty {
  std::string measure;  // one of kCountMeasures
  std::array<DifficultyBin, kCountBins> bins;
};

// Steps that ended past a joint limit after integration, summed over the
// group's runs whose summaries count them (format 3 on): position limits over
// `counted_steps`, velocity limits over `velocity_counted_steps` (runs with
// velocity limits). Zero counted steps: no run says.
struct LimitSteps {
  long counted_steps = 0, position = 0;
  long velocity_counted_steps = 0, velocity = 0;
};

struct GroupStats {
  std::string sweep, config_key, family;
  size_t n = 0, successes = 0;
  double success_rate = 0;
  Interval success_interval;
  double median_min_distance = 0, p10_min_distance = 0;  // NaN: no run with a finite one
  double median_max_tracking_error = 0;
  double joint_limit_share = 0, nonfinite_share = 0;
  LimitSteps limit_steps;
  double step_us_p50 = 0, step_us_p99 = 0;  // medians over runs of each run's p50 / p99
  double median_rms_jerk = 0;  // over runs with one (rad/s³); NaN: none had
  std::map<std::string, size_t> failure_modes;  // failed runs by first failure mode
  double step_ratio_to_pinv = std::numeric_limits<double>::quiet_NaN();  // NaN: no pinv group to compare with
  // Success against the case's difficulty (generated cases): `difficulty_measure` is the
  // witness's "clearance" where the family's cases have obstacles, else its "limit_margin";
  // the bins split the family's cases at the quartiles of that measure (the same bins for
  // every configuration of the family). Empty for cases without a witness.
  std::string difficulty_measure;
  std::vector<DifficultyBin> by_difficulty;
  // Success against each obstacle count (kCountMeasures order) that the
  // family's cases carry and that puts them in two bins or more (one bin
  // separates nothing); the same measures for every configuration of the family.
  std::vector<CountDifficulty> by_count;
};

struct WinLossTie {
  size_t wins = 0, losses = 0, ties = 0;
};

struct PairedComparison {
  std::string sweep, a, b;  // configuration keys; wins are a's
  size_t cases = 0;
  WinLossTie success, min_distance;
};

// One configuration against a reference configuration on one family's cases.
struct FamilyComparison {
  std::string sweep, family, config_key, reference;  // wins are config_key's
  std::string role;                                   // "pinv" or "best"
  size_t cases = 0;
  WinLossTie success;
  double mcnemar_p = 1;
};

// How a family's verdict reads.
enum class VerdictStatus {
  kContenders,   // the best and every configuration not separated from it
  kTooFewCases,  // the cases detect no difference of kSeparableDifference: nothing listed
  kNoSuccess,    // no configuration succeeded on any case
};

// Which method when: the family's best and those not significantly worse.
// A configuration without a success is never listed when the best has one.
// `detectable`: the smallest difference in success (a share) the cases
// detect, with power 0.8 at p < 0.05 (sweep_power.hpp), on the comparisons
// with the best that found no difference (the runner-up's when every other
// configuration is significantly worse; every case discordant when there is
// no other), at their fewest cases and the largest 95 % upper Wilson bound of
// their discordant shares (`discordance`). Past kSeparableDifference
// (while some comparison found no difference) the status is kTooFewCases,
// with the cases a difference of kSeparableDifference needs at it.
struct FamilyVerdict {
  std::string sweep, family, best;
  std::vector<size_t> contenders;  // indices into SweepReport::groups: the best first, then by success rate
  size_t best_group = 0;           // the best's index into SweepReport::groups
  VerdictStatus status = VerdictStatus::kContenders;
  size_t cases = 0;  // the best's
  double detectable = 0, discordance = 1;  // detectable: +inf when no difference can be
  size_t cases_needed = 0;                 // kTooFewCases only
};

inline constexpr double kSignificance = 0.05;
inline constexpr double kSeparableDifference = 0.20;
// Every two configurations are paired only up to this many in a sweep (32: at
// most 496 pairs); the report grows linearly in configurations x families.
inline constexpr size_t kMaxPairedConfigs = 32;
inline constexpr double kStepTimeShift = 1.0;  // µs

struct RankEntry {
  std::string sweep, config_key;
  size_t n = 0;
  double success_rate = 0, median_max_tracking_error = 0;
};

struct SweepReport {
  std::vector<std::string> sweeps;
  std::vector<GroupStats> groups;       // by sweep, configuration, family
  std::vector<PairedComparison> pairs;  // by sweep, then a, b (sweeps of at most kMaxPairedConfigs)
  std::map<std::string, size_t> pairs_omitted;  // sweep -> its configurations, where pairs were left out
  std::vector<RankEntry> ranking;       // by sweep, best first
  std::vector<FamilyComparison> comparisons;  // by sweep, family, then configuration (the family's best first)
  std::vector<FamilyVerdict> verdicts;        // by sweep, family
  std::vector<FamilyFallback> fallbacks;      // by sweep, family
};

inline constexpr double kDistanceTie = 1e-9;

// Throws std::runtime_error on a stored summary that is not JSON. Linear in
// the runs (but for the pairs of a sweep of at most kMaxPairedConfigs
// configurations). `cancel` set while building: returns an incomplete report.
SweepReport build_report(const std::vector<storage::SweepRunEntry>& runs, const std::atomic<bool>* cancel = nullptr);

// The family a run is reported under: its generator family, or for scenario
// files each file on its own ("file:NAME"), so a sweep over paper scenarios
// reports per scenario.
std::string report_family(const storage::SweepRunRow& row);

}  // namespace rrlab::sweep

// What to try when the first choice fails, from one family's paired per-case
// outcomes: the best first choice A with a fallback B (a case counts as solved
// when A or B solves it), and the cases no configuration solves.
//
// The pair is an offline upper bound: B is credited with the cases it solved
// when run from the start, not from where A failed. Pair rule: the highest
// share solved by A or B, then the lowest cost (A's step time plus B's
// weighted by A's failure share), then one configuration before two (B only
// when it solves a case A fails), then the verdict's order. The witness lane
// is the certificate, not a method: it is never a candidate and never counts
// as solving a case; it only says which unsolved cases are solvable.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace rrlab::sweep {

// Pairs are taken among a family's first kMaxFallbackConfigs configurations
// (by success: every ordered pair, kMaxFallbackConfigs^2 unions of bit sets),
// so a sweep of any size costs at most that per family.
inline constexpr size_t kMaxFallbackConfigs = 64;
// A family's unsolved cases are counted in full but listed only this far.
inline constexpr size_t kMaxUnsolvedListed = 50;

// One family's outcomes, as the report pairs them.
struct FamilyOutcomes {
  std::vector<std::string> configs;  // the witness lane apart, the verdict's order (best first)
  std::vector<double> step_us;       // each configuration's step cost (median µs per step; NaN: unknown)
  struct Case {
    std::string scenario_key;
    std::uint64_t seed = 0;
    std::vector<std::int8_t> outcome;  // per configuration: -1 not run, 0 failed, 1 succeeded
    std::int8_t witness = -1;          // the witness lane's, likewise
  };
  std::vector<Case> cases;
};

struct CaseRef {
  std::string scenario_key;
  std::uint64_t seed = 0;
};

struct FamilyFallback {
  std::string sweep, family;
  size_t cases = 0;           // cases some configuration ran
  size_t solved_by_some = 0;  // of them, solved by at least one configuration
  // The first choice and its fallback (`second` empty: no configuration
  // solves a case `first` fails, among those considered).
  std::string first, second;
  size_t pair_cases = 0;                 // the cases both ran (first's alone without a second)
  size_t first_solved = 0, pair_solved = 0;
  double cost_us = std::numeric_limits<double>::quiet_NaN();  // per step; NaN: a step time unknown
  size_t configs_considered = 0, configs_total = 0;
  size_t unsolved = 0;                      // cases no configuration solves
  std::optional<size_t> witness_solves;     // of them, the witness lane's successes (none: no witness runs)
  std::vector<CaseRef> unsolved_listed;     // the first kMaxUnsolvedListed, by family, seed and index
  bool several_seeds = false;               // a case is unsolved under several run seeds (each listed with its own)
};

// Linear in cases x configurations, but for the pairs (above).
FamilyFallback family_fallback(const FamilyOutcomes& outcomes);

// Commands that write exactly the listed unsolved cases of generated
// families (`rrlab generate FAMILY --seed S --cases I,J,... --out DIR`, or
// `--perturb NAME`), one per generator and seed, in listing order; none for
// scenario files. The sweep entry's options, if it had any, must be added as
// --option KEY=VALUE: the stored runs do not keep them.
std::vector<std::string> unsolved_commands(const FamilyFallback& fallback);

}  // namespace rrlab::sweep

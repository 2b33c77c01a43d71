// What a paired comparison of success can detect: the power of the exact
// McNemar test (sweep_stats.hpp) that the report's "which method when" uses.
//
// Model: each of n cases is discordant (one configuration succeeds, the
// other fails) with probability psi, in the first's favour with probability
// p10 = (psi + delta) / 2 and against it with p01 = (psi - delta) / 2, so
// delta = p10 - p01 is the difference in success rates. The test rejects
// when, of the d discordant cases, min(wins, losses) <= k_d, k_d the largest
// k with 2 P(Binomial(d, 1/2) <= k) < alpha (none below d = 6 at 0.05).
//   power(n, psi, delta) = sum_d P(Binomial(n, psi) = d)
//                          * [P(Binomial(d, q) <= k_d) + P(Binomial(d, 1 - q) <= k_d)],
//   q = p10 / psi: exact, summed term by term over the d within 12 standard
// deviations of n psi, where the expected discordant cases n psi are at
// most kExactDiscordant (the cost grows with them, not with n); beyond, the
// normal approximation of Connor (1987),
//   power = Phi((delta sqrt(n) - z_{1-alpha/2} sqrt(psi)) / sqrt(psi - delta^2)),
// which with so many discordant cases is within a fraction of a point of the
// exact sum (with few it is not: 0.72 against 0.68 at n = 400, psi = 0.1).
#pragma once

#include <cstddef>

namespace rrlab::sweep {

inline constexpr double kPowerTarget = 0.8;
inline constexpr double kPowerAlpha = 0.05;  // two-sided
inline constexpr double kExactDiscordant = 1000;

// The probability that the exact two-sided McNemar test at kPowerAlpha
// rejects, in the model above (0 <= delta <= psi <= 1; 0 when psi is 0).
double mcnemar_power(size_t n, double psi, double delta);

// The smallest difference in success n paired cases detect with power
// kPowerTarget when the configurations differ on a share `psi` of them (the
// planning discordance). A difference larger than psi forces at least that
// much discordance, so each delta is tried at discordance max(psi, delta).
// +infinity when no difference can be detected (n < 6: no outcome of the
// exact test reaches p < 0.05).
double min_detectable_difference(size_t n, double psi);

// About how many cases detect `delta` with power kPowerTarget at discordance
// max(psi, delta): the smallest n (from Connor's formula, then checked with
// the exact power) whose power reaches the target.
size_t cases_needed(double delta, double psi);

}  // namespace rrlab::sweep

// The power of the exact McNemar test: against sums computed by hand and by
// enumerating every outcome with the report's own test, the smallest
// detectable difference and the cases a difference needs.
#include <gtest/gtest.h>

#include <cmath>

#include <rrlab/sweep/sweep_power.hpp>
#include <rrlab/sweep/sweep_stats.hpp>

namespace rrlab::sweep {
namespace {

double binomial(size_t n, size_t k, double p) {
  return std::exp(std::lgamma(double(n) + 1) - std::lgamma(double(k) + 1) - std::lgamma(double(n - k) + 1)) *
         std::pow(p, double(k)) * std::pow(1 - p, double(n - k));
}

// Every (wins, losses) outcome of n cases, rejected where mcnemar_exact_p says so.
double enumerated_power(size_t n, double psi, double delta) {
  const double p10 = (psi + delta) / 2, p01 = (psi - delta) / 2, p00 = 1 - psi;
  double power = 0;
  for (size_t w = 0; w <= n; ++w)
    for (size_t l = 0; w + l <= n; ++l) {
      if (mcnemar_exact_p(w, l) >= 0.05) continue;
      power += std::exp(std::lgamma(double(n) + 1) - std::lgamma(double(w) + 1) - std::lgamma(double(l) + 1) -
                        std::lgamma(double(n - w - l) + 1)) *
               std::pow(p10, double(w)) * std::pow(p01, double(l)) * std::pow(p00, double(n - w - l));
    }
  return power;
}

TEST(SweepPower, ExactPowerByHand) {
  EXPECT_EQ(mcnemar_power(5, 1, 1), 0);               // 2 / 2^5 = 0.0625: five cases never reach p < 0.05
  EXPECT_NEAR(mcnemar_power(6, 1, 1), 1, 1e-12);      // six wins of six: p = 0.031
  EXPECT_NEAR(mcnemar_power(6, 1, 0), 2.0 / 64, 1e-12);  // no difference: the test's own size
  // ten discordant cases, 9 : 1 expected: k_10 = 1 (2 * 11 / 1024 = 0.021; 2 * 56 / 1024 = 0.11)
  const double q = 0.9;
  const double expected = binomial(10, 0, q) + binomial(10, 1, q) + binomial(10, 9, q) + binomial(10, 10, q);
  EXPECT_NEAR(mcnemar_power(10, 1, 0.8), expected, 1e-12);
  EXPECT_EQ(mcnemar_power(100, 0, 0), 0);
}

TEST(SweepPower, ExactPowerIsTheReportsTestOverEveryOutcome) {
  for (const auto& [n, psi, delta] : {std::tuple{12, 0.4, 0.2}, {30, 0.25, 0.15}, {60, 0.1, 0.05}, {40, 0.6, 0.0}})
    EXPECT_NEAR(mcnemar_power(size_t(n), psi, delta), enumerated_power(size_t(n), psi, delta), 1e-9)
        << n << " " << psi << " " << delta;
}

TEST(SweepPower, WithoutADifferenceTheTestRejectsAtMostAlpha) {
  // many discordant cases, near even: the tails must not underflow to nothing (0.55^1400 does)
  for (const auto& [n, psi] : {std::pair{size_t(20), 0.5}, {size_t(1400), 0.7}, {size_t(1000), 1.0}, {size_t(100000), 0.005}}) {
    const double size = mcnemar_power(n, psi, 0);
    EXPECT_LE(size, kPowerAlpha) << n << " " << psi;
    EXPECT_GT(size, n > 100 ? 0.04 : 0.0) << n << " " << psi;
  }
}

TEST(SweepPower, TheApproximationTakesOverSmoothly) {
  // the exact sum at n psi = kExactDiscordant against the normal approximation just past it
  for (const auto& [n, psi, delta] : {std::tuple{size_t(10000), 0.1, 0.009}, {size_t(2000), 0.5, 0.044}, {size_t(1000), 1.0, 0.088}})
    EXPECT_NEAR(mcnemar_power(n, psi, delta), mcnemar_power(n + 1, psi, delta), 0.01) << n << " " << psi;
}

TEST(SweepPower, SmallestDetectableDifference) {
  EXPECT_TRUE(std::isinf(min_detectable_difference(3, 1)));
  EXPECT_TRUE(std::isinf(min_detectable_difference(5, 0.2)));
  // every case discordant: 100 cases detect about 28 points, 200 about 20
  const double hundred = min_detectable_difference(100, 1);
  EXPECT_GT(hundred, 0.25);
  EXPECT_LT(hundred, 0.31);
  EXPECT_LT(min_detectable_difference(200, 1), hundred);
  // few discordant cases: 100 cases detect well under 20 points
  EXPECT_LT(min_detectable_difference(100, wilson_interval(3, 100).high), 0.1);
  // the power reaches 0.8 at the difference and not below it
  for (const auto& [n, psi] : {std::pair{size_t(40), 0.3}, {size_t(100), 0.09}, {size_t(1000), 0.2}}) {
    const double d = min_detectable_difference(n, psi);
    EXPECT_GE(mcnemar_power(n, std::max(psi, d), d), kPowerTarget) << n;
    EXPECT_LT(mcnemar_power(n, std::max(psi, 0.98 * d), 0.98 * d), kPowerTarget) << n;
  }
}

TEST(SweepPower, CasesNeededForADifference) {
  const size_t worst = cases_needed(0.2, 1);  // every case discordant
  EXPECT_GT(worst, 180u);
  EXPECT_LT(worst, 215u);
  EXPECT_GE(mcnemar_power(worst, 1, 0.2), kPowerTarget);
  EXPECT_LT(mcnemar_power(worst - 1, 1, 0.2), kPowerTarget);
  // a 20-point difference makes at least 20 % of the cases discordant: the fewest cases it needs
  const size_t fewest = cases_needed(0.2, 0.01);
  EXPECT_EQ(fewest, cases_needed(0.2, 0.2));
  EXPECT_LT(fewest, 60u);
  EXPECT_GE(mcnemar_power(fewest, 0.2, 0.2), kPowerTarget);
  const size_t moderate = cases_needed(0.05, 0.5);  // Connor's formula: 1,567
  EXPECT_NEAR(double(moderate), 1567, 40);
  EXPECT_GE(mcnemar_power(moderate, 0.5, 0.05), kPowerTarget);
  EXPECT_NEAR(double(cases_needed(0.02, 1)), 19620, 2);  // past the exact sum: Connor's formula itself
}

}  // namespace
}  // namespace rrlab::sweep

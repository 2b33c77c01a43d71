#include <rrlab/util/extreme_eigenvalues.hpp>

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <limits>
#include <random>

namespace rrlab {
namespace {

using Matrix = ExtremeEigenvalues::Matrix;

// A A^T of a random m x n matrix whose singular values are `sigma` (spread or clustered as given).
Matrix gram(const Eigen::VectorXd& sigma, int cols, std::mt19937& rng) {
  std::normal_distribution<double> g;
  const int m = int(sigma.size());
  Eigen::MatrixXd u(m, m), v(cols, cols);
  for (int i = 0; i < u.size(); ++i) u.data()[i] = g(rng);
  for (int i = 0; i < v.size(); ++i) v.data()[i] = g(rng);
  const Eigen::MatrixXd qu = u.householderQr().householderQ(), qv = v.householderQr().householderQ();
  const Eigen::MatrixXd a = qu * sigma.asDiagonal() * qv.topRows(m);
  return a * a.transpose();
}

// Both ends against Eigen's QR solver: the largest to a few ulps of itself,
// the smallest to a few ulps of the largest (the accuracy either method has).
void expect_matches_qr(const Matrix& a, const char* what) {
  ExtremeEigenvalues extreme(int(a.rows()));
  extreme.compute(a);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> qr(Eigen::MatrixXd(a), Eigen::EigenvaluesOnly);
  const double lo = qr.eigenvalues()[0], hi = qr.eigenvalues()[a.rows() - 1];
  EXPECT_NEAR(extreme.max(), hi, 1e-13 * std::abs(hi)) << what;
  EXPECT_NEAR(extreme.min(), lo, 1e-13 * std::abs(hi)) << what;
}

TEST(ExtremeEigenvalues, MatchTheQrSolverOnSpreadSpectra) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-4, 1);
  int laguerre = 0, total = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int m = 1 + trial % 6;
    Eigen::VectorXd sigma(m);
    for (int i = 0; i < m; ++i) sigma[i] = std::pow(10.0, u(rng));  // condition numbers up to 1e5
    ExtremeEigenvalues extreme(m);
    const Matrix a = gram(sigma, m + 4, rng);
    extreme.compute(a);
    laguerre += extreme.iterations() >= 0, ++total;
    expect_matches_qr(a, "spread");
  }
  EXPECT_EQ(laguerre, total) << "spread spectra are Laguerre's case, not the fallback's";
}

TEST(ExtremeEigenvalues, ClusteredAndRepeatedEndsStillMatch) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 100; ++trial) {
    const int m = 2 + trial % 5;
    Eigen::VectorXd sigma = Eigen::VectorXd::LinSpaced(m, 0.5, 2.0);
    sigma[m - 1] = sigma[m - 2] * (1 + (trial % 3 == 0 ? 0.0 : 1e-9));  // a double or near-double top
    sigma[0] = sigma[1] * (1 - (trial % 2 == 0 ? 0.0 : 1e-10));        // and bottom
    expect_matches_qr(gram(sigma, m + 3, rng), "clustered");
  }
}

TEST(ExtremeEigenvalues, DiagonalSingularAndTinyMatrices) {
  Matrix d = Eigen::Vector3d(2.0, 5.0, 0.25).asDiagonal();
  expect_matches_qr(d, "diagonal");
  Matrix singular(3, 3);
  singular << 1, 2, 3, 2, 4, 6, 3, 6, 9;  // rank 1: smallest 0 to rounding
  expect_matches_qr(singular, "rank 1");
  Matrix zero = Matrix::Zero(4, 4);
  ExtremeEigenvalues extreme(4);
  extreme.compute(zero);
  EXPECT_EQ(extreme.min(), 0.0);
  EXPECT_EQ(extreme.max(), 0.0);
  Matrix scaled = 1e-150 * Matrix(Eigen::Vector4d(1, 2, 3, 4).asDiagonal());
  expect_matches_qr(scaled, "tiny entries");
  Matrix one(1, 1);
  one << 7.0;
  ExtremeEigenvalues single(1);
  single.compute(one);
  EXPECT_EQ(single.min(), 7.0);
  EXPECT_EQ(single.max(), 7.0);
}

TEST(ExtremeEigenvalues, IndefiniteAndNonFiniteInput) {
  Matrix indefinite(3, 3);
  indefinite << -1, 0.5, 0, 0.5, 2, 0.3, 0, 0.3, 0.5;  // one negative eigenvalue: the smallest from Gershgorin's bound
  expect_matches_qr(indefinite, "indefinite");
  ExtremeEigenvalues extreme(3);
  extreme.compute(indefinite);
  EXPECT_GE(extreme.iterations(), 0) << "Laguerre's path, not the fallback";
  Matrix broken = indefinite;
  broken(1, 1) = std::numeric_limits<double>::quiet_NaN();
  extreme.compute(broken);  // no hang, no throw: whatever QR makes of it
  EXPECT_EQ(extreme.iterations(), -1);
}

}  // namespace
}  // namespace rrlab

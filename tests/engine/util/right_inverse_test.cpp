#include <rrlab/util/right_inverse.hpp>

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <random>

namespace rrlab {
namespace {

Eigen::MatrixXd random_matrix(int rows, int cols, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  Eigen::MatrixXd a(rows, cols);
  for (int i = 0; i < a.size(); ++i) a.data()[i] = g(rng);
  return a;
}

TEST(RightInverse, PinvMatchesCompleteOrthogonalDecomposition) {
  for (unsigned seed = 0; seed < 20; ++seed) {
    const int rows = 1 + int(seed % 6), cols = rows + int(seed % 5);
    const Eigen::MatrixXd a = random_matrix(rows, cols, seed);
    const Eigen::VectorXd y = random_matrix(rows, 1, seed + 50);
    RightInverse inv(rows, cols);
    inv.factor_pinv(a);
    Eigen::VectorXd x(cols);
    inv.apply(y, x);
    const Eigen::VectorXd expected = a.completeOrthogonalDecomposition().pseudoInverse() * y;
    EXPECT_LT((x - expected).norm(), 1e-9 * (1 + expected.norm()));
    EXPECT_LT((a * x - y).norm(), 1e-9);
  }
}

TEST(RightInverse, RankDeficientMatrixGetsItsPseudoinverse) {
  Eigen::MatrixXd a(3, 4);
  a << 1, 2, 3, 4, 2, 4, 6, 8, 0, 1, 0, 1;  // row 2 = 2 × row 1
  RightInverse inv(3, 4);
  inv.factor_pinv(a, 1e-10);
  const Eigen::VectorXd y = Eigen::Vector3d(1, 2, 3);
  Eigen::VectorXd x(4);
  inv.apply(y, x);
  const Eigen::VectorXd expected = a.completeOrthogonalDecomposition().pseudoInverse() * y;
  EXPECT_LT((x - expected).norm(), 1e-8);
  EXPECT_NEAR(inv.sigma_min(), 0.0, 1e-6);
}

TEST(RightInverse, DampedLeastSquaresFormula) {
  const Eigen::MatrixXd a = random_matrix(3, 7, 9);
  const Eigen::VectorXd y = random_matrix(3, 1, 10);
  const double lambda = 0.3;
  RightInverse inv(3, 7);
  inv.factor_dls(a, lambda);
  Eigen::VectorXd x(7);
  inv.apply(y, x);
  const Eigen::MatrixXd aat = a * a.transpose() + lambda * lambda * Eigen::MatrixXd::Identity(3, 3);
  const Eigen::VectorXd expected = a.transpose() * aat.inverse() * y;
  EXPECT_LT((x - expected).norm(), 1e-12);
}

TEST(RightInverse, NullProjectionIsInvisibleToA) {
  const Eigen::MatrixXd a = random_matrix(4, 9, 21);
  const Eigen::VectorXd z = random_matrix(9, 1, 22);
  RightInverse inv(4, 9);
  inv.factor_pinv(a);
  Eigen::VectorXd n(9);
  inv.null_project(z, n);
  EXPECT_LT((a * n).norm(), 1e-12);
  Eigen::VectorXd nn(9);
  inv.null_project(n, nn);  // idempotent
  EXPECT_LT((nn - n).norm(), 1e-12);
}

}  // namespace
}  // namespace rrlab

#include <rrlab/util/small_lu.hpp>

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <random>

namespace rrlab {
namespace {

// SmallLu against Eigen's PartialPivLU on random matrices of every size it
// takes: the same solutions and determinants to rounding; factoring a
// Jacobian's columns in place is the factoring of the copied block, bit for bit.
TEST(SmallLu, MatchesPartialPivLuAndFactorsColumnsInPlace) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int n = 1; n <= SmallLu::kMax; ++n) {
    for (int trial = 0; trial < 50; ++trial) {
      Eigen::MatrixXd wide(n, n + 4);
      for (int r = 0; r < n; ++r)
        for (int c = 0; c < n + 4; ++c) wide(r, c) = u(rng);
      int cols[SmallLu::kMax];
      for (int c = 0; c < n; ++c) cols[c] = (3 * c + trial) % (n + 4);
      bool distinct = true;
      for (int c = 0; c < n; ++c)
        for (int d = 0; d < c; ++d) distinct &= cols[c] != cols[d];
      if (!distinct) continue;
      Eigen::MatrixXd block(n, n);
      for (int c = 0; c < n; ++c) block.col(c) = wide.col(cols[c]);
      Eigen::VectorXd b(n), x(n), y(n);
      for (int r = 0; r < n; ++r) b[r] = u(rng);

      SmallLu lu, in_place;
      lu.compute(block);
      in_place.compute_columns(wide, cols);
      lu.solve(b, x);
      in_place.solve(b, y);
      const Eigen::PartialPivLU<Eigen::MatrixXd> reference(block);
      const Eigen::VectorXd expected = reference.solve(b);
      const double scale = 1 + expected.cwiseAbs().maxCoeff();
      EXPECT_LT((x - expected).cwiseAbs().maxCoeff(), 1e-9 * scale) << "n " << n;
      EXPECT_NEAR(lu.determinant(), reference.determinant(), 1e-12 * (1 + std::abs(reference.determinant())));
      EXPECT_EQ(x, y);  // the same operations on the same numbers
      EXPECT_EQ(lu.determinant(), in_place.determinant());
    }
  }
}

// A singular matrix (a zero column) is factored all the same: determinant 0.
TEST(SmallLu, ASingularMatrixHasDeterminantZero) {
  Eigen::MatrixXd a(4, 4);
  a << 1, 2, 0, 4,  //
      -2, 1, 0, 3,  //
      0.5, 7, 0, -1,  //
      3, -4, 0, 2;
  SmallLu lu;
  lu.compute(a);
  EXPECT_EQ(lu.determinant(), 0.0);
}

}  // namespace
}  // namespace rrlab

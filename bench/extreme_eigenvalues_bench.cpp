// The two ends of the spectrum of a 6 x 6 J Jᵀ (direct_search's DM per
// option): rrlab's ExtremeEigenvalues against Eigen's SelfAdjointEigenSolver
// (all eigenvalues, QR) in the same process. 64 matrices J Jᵀ of seeded
// random 6 x 10 Jacobians, condition numbers up to about 1e4.
#include <benchmark/benchmark.h>

#include <Eigen/Eigenvalues>
#include <random>
#include <vector>

#include <rrlab/util/extreme_eigenvalues.hpp>

namespace rrlab {
namespace {

std::vector<ExtremeEigenvalues::Matrix> spd_matrices() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<ExtremeEigenvalues::Matrix> out;
  for (int i = 0; i < 64; ++i) {
    Eigen::MatrixXd j(6, 10);
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 10; ++c) j(r, c) = u(rng);
    j.row(i % 6) *= std::pow(10.0, -2.0 * (i % 3));  // a row scaled down: ill-conditioned
    out.push_back(j * j.transpose());
  }
  return out;
}

void BM_extreme_eigenvalues_6x6(benchmark::State& state) {
  const auto matrices = spd_matrices();
  ExtremeEigenvalues solver(6);
  std::size_t i = 0;
  for (auto _ : state) {
    solver.compute(matrices[i++ % matrices.size()]);
    benchmark::DoNotOptimize(solver.max());
  }
  // Laguerre iterations per matrix (both ends), and the share the QR fallback answered
  double iterations = 0, fallbacks = 0;
  for (const auto& m : matrices) {
    solver.compute(m);
    if (solver.iterations() < 0) fallbacks += 1;
    else iterations += solver.iterations();
  }
  state.counters["iterations"] = iterations / (matrices.size() - fallbacks);
  state.counters["qr_fallback"] = fallbacks / matrices.size();
}
BENCHMARK(BM_extreme_eigenvalues_6x6);

void BM_eigen_selfadjoint_eigenvalues_6x6(benchmark::State& state) {
  const auto matrices = spd_matrices();
  Eigen::SelfAdjointEigenSolver<ExtremeEigenvalues::Matrix> solver(6);
  std::size_t i = 0;
  for (auto _ : state) {
    solver.compute(matrices[i++ % matrices.size()], Eigen::EigenvaluesOnly);
    benchmark::DoNotOptimize(solver.eigenvalues()[5]);
  }
}
BENCHMARK(BM_eigen_selfadjoint_eigenvalues_6x6);

}  // namespace
}  // namespace rrlab

// Dense Goldfarb–Idnani QP (engine/util/qp_solver): 7 variables, 6
// equalities, 30 general inequalities and a box, as a 6-D task on a 7-DOF
// arm with joint bounds and obstacle rows. A sequence of slowly changing
// problems (as from consecutive control steps) is solved warm-started; the
// cold variant forgets the previous active set each time.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include <rrlab/util/qp_solver.hpp>

namespace rrlab {
namespace {

constexpr int kN = 7, kEq = 6, kIneq = 30, kSequence = 64;

// Problems along a smooth path: data = base + sin(phase) · drift.
std::vector<QpProblem> problem_sequence() {
  std::mt19937 rng(42);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  QpProblem base(kN, kEq, kIneq), drift(kN, kEq, kIneq);
  base.H = Eigen::MatrixXd::Identity(kN, kN);
  Eigen::VectorXd x0(kN);
  for (int i = 0; i < kN; ++i) x0[i] = 0.3 * normal(rng);
  for (QpProblem* p : {&base, &drift}) {
    p->eq_count = kEq;
    p->ineq_count = kIneq;
    for (int k = 0; k < kEq; ++k)
      for (int i = 0; i < kN; ++i) p->A_eq(k, i) = normal(rng);
    for (int k = 0; k < kIneq; ++k)
      for (int i = 0; i < kN; ++i) p->A_in(k, i) = normal(rng);
  }
  drift.A_eq *= 0.02;
  drift.A_in *= 0.02;
  base.b_eq = base.A_eq * x0;
  for (int k = 0; k < kIneq; ++k) base.b_in[k] = base.A_in.row(k).dot(x0) - 0.3 * unit(rng);
  base.lower.setConstant(-1.0);
  base.upper.setConstant(1.0);
  std::vector<QpProblem> seq;
  for (int s = 0; s < kSequence; ++s) {
    QpProblem p = base;
    const double w = std::sin(2 * M_PI * s / kSequence);
    p.A_eq += w * drift.A_eq;
    p.A_in += w * drift.A_in;
    p.g.setZero();
    seq.push_back(p);
  }
  return seq;
}

void solve_sequence(benchmark::State& state, bool warm) {
  const std::vector<QpProblem> seq = problem_sequence();
  QpSolver solver(kN, kEq, kIneq);
  solver.set_warm_start(warm);
  size_t i = 0;
  long active = 0, solves = 0;
  for (auto _ : state) {
    const QpStatus status = solver.solve(seq[i]);
    benchmark::DoNotOptimize(status);
    active += solver.active_inequalities();
    ++solves;
    i = (i + 1) % seq.size();
  }
  state.counters["active_ineq"] = static_cast<double>(active) / std::max(1L, solves);
}

void BM_Qp7x6x30Warm(benchmark::State& state) { solve_sequence(state, true); }
void BM_Qp7x6x30Cold(benchmark::State& state) { solve_sequence(state, false); }
BENCHMARK(BM_Qp7x6x30Warm)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_Qp7x6x30Cold)->Repetitions(5)->ReportAggregatesOnly(true);

}  // namespace
}  // namespace rrlab

// qp_ik: differential inverse kinematics as one weighted QP, the formulation
// of the mink and pink libraries (S. Caron et al.; written from their
// documentation, "Differential inverse kinematics" in pink's and mink's docs,
// not from their code), with the velocity dampers of Faverjon & Tournassoud
// (1987) for collisions:
//
//   minimise  w_t ‖J q̇ − v‖² + w_p ‖q̇ − k_p (q_rest − q)‖² + λ ‖q̇‖²
//             λ = λ_0 + μ ‖e‖²                  (Levenberg–Marquardt damping scaled by the task error e)
//   s.t.      lower ≤ q̇ ≤ upper                 (joint range with gain γ, velocity, acceleration, step cap)
//             ḋ_k ≥ −ξ (d_k − d_s)/(d_i − d_s)   (every obstacle and self pair with d_k < d_i)
//
// v = ẋ_ff + K e is the simulator's commanded task velocity. The task is a
// cost, not a constraint, so only the dampers can conflict with the box; when
// they do, each row gives way by its least violation within the box (the
// first level of hqp, velocity_constraints.hpp) and the QP is solved again:
// the step never fails. Constraints: velocity_constraints.cpp; shared
// parameters: constrained_velocity_method.cpp.
//
// In QP form (½xᵀHx + gᵀx, the factor 2 dropped):
//   H = w_t JᵀJ + (w_p + λ + 10⁻⁹) I,  g = −w_t Jᵀv − w_p k_p (q_rest − q)
#include <rrlab/methods/constrained_velocity_method.hpp>
#include <rrlab/methods/factories.hpp>

namespace rrlab {
namespace {

constexpr double kQpIkFloor = 1e-9;  // H stays positive definite with every weight at 0

class QpIk final : public ConstrainedVelocityMethod {
  const ParamSlot kTaskWeight = slot("task_weight"), kDamping = slot("damping"), kLmDamping = slot("lm_damping");

 public:
  explicit QpIk(const MethodContext& ctx)
      : ConstrainedVelocityMethod(qp_ik_params(), ctx),
        n_(ctx.model.dof()),
        problem_(n_, 0, row_capacity()),
        solver_(n_, 0, row_capacity()),
        residual_(task_rows(ctx.space)) {
    residual_diag_ = declare_diagnostic("task_residual");
    damping_diag_ = declare_diagnostic("lm_damping");
  }

  void step(const StepInput& in, StepOutput& out) override {
    if (in.state.step == 0) solver_.forget_warm_start();
    prepare(in);
    const Eigen::MatrixXd& J = in.task_jacobian;
    const double w_t = p(kTaskWeight), w_p = posture_weight();
    const double lambda = p(kDamping) + p(kLmDamping) * in.ref.error.squaredNorm();  // λ = λ_0 + μ‖e‖²
    problem_.H.noalias() = w_t * J.transpose() * J;
    problem_.H.diagonal().array() += w_p + lambda + kQpIkFloor;
    problem_.g.noalias() = -w_t * J.transpose() * in.ref.xdot;
    problem_.g -= w_p * posture_velocity();
    problem_.lower = constraints_.lower;
    problem_.upper = constraints_.upper;
    load_rows();
    QpStatus status = solver_.solve(problem_);
    if (status != QpStatus::optimal) {  // with no rows too: the least-violation q̇ is the fallback
      relax_dampers();  // rows ask A q̇ ≥ b − w*
      load_rows();
      status = solver_.solve(problem_);
    }
    out.qdot = status == QpStatus::optimal ? solver_.x() : least_violation_qdot();
    residual_.noalias() = J * out.qdot;
    residual_ -= in.ref.xdot;
    report(solver_, status, 0, out.qdot, out);
    out.diag.values[residual_diag_] = residual_.norm();
    out.diag.values[damping_diag_] = lambda;
  }

 private:
  void resize_problems() override {
    problem_ = QpProblem(n_, 0, row_capacity());
    solver_ = QpSolver(n_, 0, row_capacity());
  }
  void load_rows() {
    const int rows = constraints_.rows;
    problem_.ineq_count = rows;
    problem_.A_in.topRows(rows) = constraints_.A.topRows(rows);
    problem_.b_in.head(rows) = constraints_.b.head(rows);
  }

  int n_;
  QpProblem problem_;
  QpSolver solver_;
  Eigen::VectorXd residual_;
  int residual_diag_, damping_diag_;
};

}  // namespace

std::vector<ParamSpec> qp_ik_params() {
  return with_velocity_constraint_params({{"task_weight", "Task weight w_t", "", "weight of the task cost ‖J q̇ − v‖²", 1.0, 0.0, 1e6, 0.1, {}},
          {"damping", "Damping λ_0", "", "fixed part of the Levenberg–Marquardt damping λ‖q̇‖²", 1e-4, 0.0, 10.0,
           1e-4, {}},
          {"lm_damping", "Error-scaled damping μ", "1/m²",
           "λ = λ_0 + μ‖e‖², e the task error: more damping while the target is out of reach", 1.0, 0.0, 1e4, 0.1,
           {}}});
}

std::unique_ptr<Method> make_qp_ik(const MethodContext& ctx) { return std::make_unique<QpIk>(ctx); }

}  // namespace rrlab

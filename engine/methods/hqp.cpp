// hqp: a strict hierarchy of three levels with inequalities, solved as a
// cascade of QPs (O. Kanoun, F. Lamiraux & P.-B. Wieber, "Kinematic control
// of redundant manipulators: generalizing the task-priority framework to
// inequality task", IEEE T-RO 2011; A. Escande, N. Mansard & P.-B. Wieber,
// "Hierarchical quadratic programming: fast online humanoid-robot motion
// generation", IJRR 2014). Each level is optimised without degrading the
// levels above: their optimal residuals are kept as constraints.
//
//   level 1 (hard constraints): the box (joint range with gain γ, velocity,
//     acceleration, step cap) and the velocity dampers A q̇ ≥ b on obstacle
//     and self pairs (Faverjon & Tournassoud). When the dampers cannot all
//     hold within the box: their least violation
//         w* = argmin ½‖w‖² + ½ε‖q̇‖²  s.t. A q̇ + w ≥ b, w ≥ 0, q̇ in the box
//     (velocity_constraints.hpp), and A q̇ ≥ b − w* from then on.
//   level 2 (the task): min ½‖J q̇ − v‖² + ½ε_t‖q̇‖² subject to level 1;
//     its optimal residual s* = J q̇₂ − v (least squares when infeasible).
//   level 3 (posture): min ½w_p‖q̇ − k_p(q_rest − q)‖² + ½·10⁻⁹‖q̇‖²
//     subject to level 1 and J q̇ = v + s* (level 2's residual fixed).
//
// The first solve is level 2 with the rows as they are: only when it is
// infeasible does level 1 run (its w* is 0 whenever the rows can hold), so a
// step costs two QPs, three when the dampers conflict. ε_t (`task_damping`)
// keeps level 2 bounded at singularities; 0 gives the undamped least squares.
#include <rrlab/methods/constrained_velocity_method.hpp>
#include <rrlab/methods/factories.hpp>

namespace rrlab {
namespace {

constexpr double kHqpFloor = 1e-9;  // the levels' Hessians stay positive definite

class Hqp final : public ConstrainedVelocityMethod {
  const ParamSlot kTaskDamping = slot("task_damping");

 public:
  explicit Hqp(const MethodContext& ctx)
      : ConstrainedVelocityMethod(hqp_params(), ctx),
        n_(ctx.model.dof()),
        m_(task_rows(ctx.space)),
        task_(n_, 0, row_capacity()),
        posture_(n_, m_, row_capacity()),
        task_solver_(n_, 0, row_capacity()),
        posture_solver_(n_, m_, row_capacity()),
        task_qdot_(n_),
        residual_(m_) {
    task_slack_ = declare_diagnostic("task_slack");
    posture_slack_ = declare_diagnostic("posture_slack");
    priority_loss_ = declare_diagnostic("priority_loss");
    level_ = declare_diagnostic("levels_solved");
  }

  void step(const StepInput& in, StepOutput& out) override {
    if (in.state.step == 0) task_solver_.forget_warm_start(), posture_solver_.forget_warm_start();
    prepare(in);
    const Eigen::MatrixXd& J = in.task_jacobian;
    const Eigen::VectorXd& v = in.ref.xdot;

    // level 2 under level 1 (level 1 solved only when the rows conflict)
    task_.H.noalias() = J.transpose() * J;
    task_.H.diagonal().array() += p(kTaskDamping) + kHqpFloor;
    task_.g.noalias() = -J.transpose() * v;
    task_.lower = constraints_.lower;
    task_.upper = constraints_.upper;
    load_rows(task_);
    QpStatus status = task_solver_.solve(task_);
    if (status != QpStatus::optimal) {  // with no rows too: the least-violation q̇ is the fallback
      relax_dampers();
      load_rows(task_);
      status = task_solver_.solve(task_);
    }
    if (status != QpStatus::optimal) {  // not expected: level 1's own q̇
      out.qdot = least_violation_qdot();
      finish(out, task_solver_, status, 1);
      return;
    }
    task_qdot_ = task_solver_.x();
    residual_.noalias() = J * task_qdot_;  // v + s*
    const double task_slack = (residual_ - v).norm();

    // level 3: posture, J q̇ = v + s* kept exactly
    const double w_p = posture_weight();
    posture_.H.setIdentity();
    posture_.H *= w_p + kHqpFloor;
    posture_.g = -w_p * posture_velocity();
    posture_.eq_count = m_;
    posture_.A_eq.topRows(m_) = J;
    posture_.b_eq.head(m_) = residual_;
    posture_.lower = constraints_.lower;
    posture_.upper = constraints_.upper;
    load_rows(posture_);
    const QpStatus posture_status = posture_solver_.solve(posture_);
    const bool third = posture_status == QpStatus::optimal;
    out.qdot = third ? posture_solver_.x() : task_qdot_;
    residual_.noalias() = J * out.qdot;
    residual_ -= v;
    out.diag.values[task_slack_] = task_slack;
    out.diag.values[priority_loss_] = std::max(0.0, residual_.norm() - task_slack);
    finish(out, third ? posture_solver_ : task_solver_, third ? posture_status : status, third ? 3 : 2);
  }

 private:
  void finish(StepOutput& out, const QpSolver& used, QpStatus status, int levels) {
    report(used, status, 0, out.qdot, out);
    out.diag.values[posture_slack_] = (out.qdot - posture_velocity()).norm();
    out.diag.values[level_] = levels;
  }
  void resize_problems() override {
    task_ = QpProblem(n_, 0, row_capacity());
    posture_ = QpProblem(n_, m_, row_capacity());
    task_solver_ = QpSolver(n_, 0, row_capacity());
    posture_solver_ = QpSolver(n_, m_, row_capacity());
  }
  void load_rows(QpProblem& qp) const {
    const int rows = constraints_.rows;
    qp.ineq_count = rows;
    qp.A_in.topRows(rows) = constraints_.A.topRows(rows);
    qp.b_in.head(rows) = constraints_.b.head(rows);
  }

  int n_, m_;
  QpProblem task_, posture_;
  QpSolver task_solver_, posture_solver_;
  Eigen::VectorXd task_qdot_, residual_;
  int task_slack_, posture_slack_, priority_loss_, level_;
};

}  // namespace

std::vector<ParamSpec> hqp_params() {
  return with_velocity_constraint_params({{"task_damping", "Task damping ε_t", "",
           "ε_t of level 2, ½‖J q̇ − v‖² + ½ε_t‖q̇‖²: bounds q̇ near singularities; 0 = undamped least squares",
           1e-4, 0.0, 10.0, 1e-4, {}}});
}

std::unique_ptr<Method> make_hqp(const MethodContext& ctx) { return std::make_unique<Hqp>(ctx); }

}  // namespace rrlab

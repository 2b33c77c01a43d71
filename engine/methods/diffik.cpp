// diffik: Drake's DifferentialInverseKinematics (R. Tedrake and the Drake
// developers, "Drake: model-based design and verification for robotics";
// the formulation of DoDifferentialInverseKinematics in its documentation):
// the commanded task velocity is scaled down, never bent. Each step solves
//
//   maximise  α − (posture cost)/c            over q̇ and α ∈ [0, 1]
//   s.t.      J q̇ = α v                       (the hand moves along v, slower when α < 1)
//             lower ≤ q̇ ≤ upper               (joint range with gain γ, velocity, acceleration, step cap)
//             ḋ_k ≥ −ξ (d_k − d_s)/(d_i − d_s) (velocity dampers, Faverjon & Tournassoud 1987)
//
// in QP form, x = [q̇; α]:
//   minimise −c α + ½w_p‖P(q̇ − k_p(q_rest − q))‖² + ½ε‖q̇‖² + ½ε α²
// with P = I − J⁺J the null-space projector (the posture acts only where the
// task does not; Drake's nominal-posture cost), c = `alpha_weight` (Drake:
// 100) and ε = 10⁻⁶ to keep the QP strictly convex. When the dampers cannot
// all hold even at α = 0, each gives way by its least violation within the
// box (velocity_constraints.hpp) and the QP is solved again; when J q̇ = α v
// still cannot hold (the box keeps the arm moving, e.g. braking at an
// acceleration limit), the step takes the least-violation q̇ and reports
// `direction_kept` 0.
#include <Eigen/Cholesky>

#include <rrlab/methods/constrained_velocity_method.hpp>
#include <rrlab/methods/factories.hpp>

namespace rrlab {
namespace {

constexpr double kDiffIkRegularisation = 1e-6;  // ε on q̇ and α
constexpr double kProjectorDamping = 1e-10;     // JJᵀ + δI: J⁺ stays defined at a singularity

class DiffIk final : public ConstrainedVelocityMethod {
  const ParamSlot kAlphaWeight = slot("alpha_weight");

 public:
  explicit DiffIk(const MethodContext& ctx)
      : ConstrainedVelocityMethod(diffik_params(), ctx),
        n_(ctx.model.dof()),
        m_(task_rows(ctx.space)),
        problem_(n_ + 1, m_, row_capacity()),
        solver_(n_ + 1, m_, row_capacity()),
        jjt_(m_, m_),
        llt_(m_),
        pinv_part_(m_, n_),
        projector_(n_, n_),
        residual_(m_) {
    alpha_ = declare_diagnostic("alpha");
    direction_kept_ = declare_diagnostic("direction_kept");
    direction_error_ = declare_diagnostic("direction_error");
    scaled_steps_ = declare_diagnostic("scaled_steps");
  }

  void step(const StepInput& in, StepOutput& out) override {
    if (in.state.step == 0) solver_.forget_warm_start(), scaled_count_ = 0;
    prepare(in);
    const Eigen::MatrixXd& J = in.task_jacobian;
    const Eigen::VectorXd& v = in.ref.xdot;
    null_space_projector(J);
    const double w_p = posture_weight();
    problem_.H.topLeftCorner(n_, n_) = w_p * projector_;
    problem_.H.diagonal().array() += kDiffIkRegularisation;
    problem_.g.head(n_).noalias() = -w_p * (projector_ * posture_velocity());
    problem_.g[n_] = -p(kAlphaWeight);
    problem_.eq_count = m_;
    problem_.A_eq.topLeftCorner(m_, n_) = J;  // J q̇ − α v = 0
    problem_.A_eq.col(n_).head(m_) = -v;
    problem_.b_eq.head(m_).setZero();
    problem_.lower.head(n_) = constraints_.lower;
    problem_.upper.head(n_) = constraints_.upper;
    problem_.lower[n_] = 0.0;
    problem_.upper[n_] = 1.0;
    load_rows();
    QpStatus status = solver_.solve(problem_);
    if (status != QpStatus::optimal) {  // with no rows too: the least-violation q̇ is the fallback
      relax_dampers();
      load_rows();
      status = solver_.solve(problem_);
    }
    const bool kept = status == QpStatus::optimal;
    double alpha = 0;
    if (kept) {
      out.qdot = solver_.x().head(n_);
      alpha = solver_.x()[n_];
    } else {
      out.qdot = least_violation_qdot();
    }
    residual_.noalias() = J * out.qdot;
    residual_ -= alpha * v;
    scaled_count_ += alpha < 1.0 - 1e-9;
    report(solver_, status, 0, out.qdot, out);
    out.diag.values[alpha_] = alpha;
    out.diag.values[direction_kept_] = kept;
    out.diag.values[direction_error_] = residual_.norm();
    out.diag.values[scaled_steps_] = double(scaled_count_);
  }

 private:
  // P = I − Jᵀ(JJᵀ + δI)⁻¹J
  void null_space_projector(const Eigen::MatrixXd& J) {
    jjt_.noalias() = J * J.transpose();
    jjt_.diagonal().array() += kProjectorDamping;
    llt_.compute(jjt_);
    pinv_part_ = J;
    llt_.solveInPlace(pinv_part_);
    projector_.noalias() = -J.transpose() * pinv_part_;
    projector_.diagonal().array() += 1.0;
  }
  void resize_problems() override {
    problem_ = QpProblem(n_ + 1, m_, row_capacity());
    solver_ = QpSolver(n_ + 1, m_, row_capacity());
  }
  void load_rows() {
    const int rows = constraints_.rows;
    problem_.ineq_count = rows;
    problem_.A_in.topLeftCorner(rows, n_) = constraints_.A.topRows(rows);
    problem_.A_in.col(n_).head(rows).setZero();
    problem_.b_in.head(rows) = constraints_.b.head(rows);
  }

  int n_, m_;
  QpProblem problem_;
  QpSolver solver_;
  Eigen::MatrixXd jjt_;
  Eigen::LLT<Eigen::MatrixXd> llt_;
  Eigen::MatrixXd pinv_part_, projector_;
  Eigen::VectorXd residual_;
  long scaled_count_ = 0;
  int alpha_, direction_kept_, direction_error_, scaled_steps_;
};

}  // namespace

std::vector<ParamSpec> diffik_params() {
  return with_velocity_constraint_params({{"alpha_weight", "Scale weight c", "",
           "c of −c α: how much more the task speed counts than the posture (Drake: 100)", 100.0, 1e-3, 1e6, 1.0,
           {}}});
}

std::unique_ptr<Method> make_diffik(const MethodContext& ctx) { return std::make_unique<DiffIk>(ctx); }

}  // namespace rrlab

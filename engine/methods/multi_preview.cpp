// Zhang, Nakamura, Yang, Song, Minami, Yanou, Deng: multi-preview control
// (Zhang, Nakamura, Yang, Song, Minami, Yanou, Deng, "Conceptual configuration control of redundant manipulators inheriting local/global merits: multi-preview control"). Each step, for the preview times t_i* = t + i·t̃ (i = 1..p), a
// 1-step GA keeps finding the configuration q̃_d(t_i*) of an imaginary
// manipulator whose hand is on r_d(t_i*) and whose AMSIP ¹S = ¹E + U is
// largest (eq. 18–22; multi_preview_avoidance.hpp, multi_preview_ga.hpp). The
// actual arm follows the hand task and is pulled toward the previews in the
// null space:
//   q̇_d = J⁺ṙ_d + (I − J⁺J) v                                  (eq. 23)
//   v = K_v [q̃_d(t_1*) − q]                        single preview (eq. 24)
//   v = K_v [Σ k_i q̃_d(t_i*) − q], Σ k_i = 1       multi-preview  (eq. 25)
// previews = 0 is the paper's p = ∞, path planning: before the first step the
// whole trajectory is planned offline (GA at knots every plan_interval, then
// the most AMSIP-rich reachable chain of candidates by dynamic programming)
// and v = K_v [q*(t) − q] + q̇*(t) follows that plan.
// Choices where the paper is silent: ṙ_d is the simulator's closed-loop task
// velocity; K_v = kv·I; the weights k_1..k_p are normalised to sum 1 (with all
// zero, equal weights); circular joints (revolute without limits) are pulled
// the short way round; obstacles are predicted at t_i* at constant velocity;
// on its first step each preview's population is evolved warmup_generations
// generations (the GA was running before the arm started).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <rrlab/methods/factories.hpp>
#include <rrlab/methods/multi_preview_avoidance.hpp>
#include <rrlab/methods/multi_preview_ga.hpp>
#include <rrlab/util/right_inverse.hpp>
#include <rrlab/util/rng.hpp>

namespace rrlab {
namespace {

constexpr int kMaxPreviews = 3;
constexpr int kMaxPopulation = 200;
constexpr double kPlanJointSpeed = 0.5;  // rad/s (m/s): reachability bound of the planner without velocity limits
constexpr double kUnreachablePenalty = 1e3;  // AMSIP lost per rad a plan step exceeds that bound

class MultiPreview final : public Method {
  // Parameters by name (Method::slot); preview i's weight is kK[i].
  const ParamSlot kPreviews = slot("previews"), kPreviewTime = slot("preview_time"), kKv = slot("kv"),
                  kPopulation = slot("population"), kGenerations = slot("generations"), kMutation = slot("mutation"),
                  kPotentialWidth = slot("potential_width"), kPotentialHeight = slot("potential_height"),
                  kWarmup = slot("warmup_generations"), kPlanInterval = slot("plan_interval");
  const ParamSlot kK[kMaxPreviews] = {slot("k1"), slot("k2"), slot("k3")};

 public:
  explicit MultiPreview(const MethodContext& ctx)
      : Method(multi_preview_params()),
        n_(ctx.model.dof()),
        arm_(ctx.model, ctx.space),
        actual_(ctx.model, ctx.space),
        plan_population_(ctx.model.dof(), kMaxPopulation),
        rng_(ctx.seed),
        inverse_(task_rows(ctx.space), ctx.model.dof()),
        target_(n_),
        v_(n_),
        null_v_(n_),
        plan_q_(n_),
        plan_next_(n_),
        velocity_limits_(ctx.model.limits.velocity) {
    for (int i = 0; i < kMaxPreviews; ++i) populations_.emplace_back(n_, kMaxPopulation);
    for (int i = 0; i < kMaxPreviews; ++i) previews_.push_back(Eigen::VectorXd::Zero(n_));
    for (int i = 0; i < kMaxPreviews; ++i) preview_s_.push_back(0.0);
    amsi_ = declare_diagnostic("amsi");
    amsip_ = declare_diagnostic("amsip");
    potential_ = declare_diagnostic("potential");
    for (int i = 0; i < kMaxPreviews; ++i) preview_diag_[i] = declare_diagnostic("preview" + std::to_string(i + 1) + "_amsip");
    evaluations_ = declare_diagnostic("ga_evaluations");
    gap_ = declare_diagnostic("preview_gap");
    null_speed_ = declare_diagnostic("null_speed");
    const JointBox& box = arm_.box();
    circular_ = box.circular;
  }

  void step(const StepInput& in, StepOutput& out) override {
    arm_.set_potential(p(kPotentialWidth), p(kPotentialHeight));
    const GaSettings settings{int(std::lround(p(kPopulation))), int(std::lround(p(kGenerations))), p(kMutation)};
    const int previews = int(std::lround(p(kPreviews)));
    const double t = in.state.t;
    int evaluations = 0;
    const int ghost_count = previews == 0 ? kMaxPreviews : previews;
    if (int(out.overlays.ghosts.size()) != ghost_count)  // only when `previews` changed
      out.overlays.ghosts.assign(ghost_count, Eigen::VectorXd::Zero(n_));

    if (previews == 0) {
      // p = ∞: path planning (offline, once)
      if (plan_.cols() == 0) evaluations += plan(in, settings);
      plan_at(t, plan_q_);
      plan_at(t + in.dt, plan_next_);
      unwrap_near(in.state.q, plan_q_);
      unwrap_near(plan_q_, plan_next_);
      target_ = plan_q_;
      v_ = p(kKv) * (plan_q_ - in.state.q) + (plan_next_ - plan_q_) / in.dt;
      for (int i = 0; i < kMaxPreviews; ++i) {
        plan_at(t + (i + 1) * p(kPreviewTime), out.overlays.ghosts[i]);
        preview_s_[i] = 0;
      }
    } else {
      // Zhang eq. 24–25: v = K_v [Σ k_i q̃_d(t_i*) − q]
      double weight_sum = 0;
      for (int i = 0; i < previews; ++i) weight_sum += p(kK[i]);
      target_.setZero();
      for (int i = 0; i < previews; ++i) {
        const double ahead = (i + 1) * p(kPreviewTime);
        evaluations += evolve_preview(in, i, t + ahead, ahead, settings);
        previews_[i] = populations_[i].best();
        unwrap_near(in.state.q, previews_[i]);
        const double k = weight_sum > 0 ? p(kK[i]) / weight_sum : 1.0 / previews;
        target_ += k * previews_[i];
        out.overlays.ghosts[i] = populations_[i].best();
        preview_s_[i] = populations_[i].best_evaluation().amsip;
      }
      v_ = p(kKv) * (target_ - in.state.q);
    }

    // Zhang eq. 23: q̇_d = J⁺ṙ_d + (I − J⁺J) v
    inverse_.factor_pinv(in.task_jacobian);
    inverse_.apply(in.ref.xdot, out.qdot);
    inverse_.null_project(v_, null_v_);
    out.qdot += null_v_;

    report(in, out, previews, evaluations);
  }

 private:
  // Evolves preview i's population at its target; the first time it runs
  // warmup generations, starting from the previous preview's population.
  int evolve_preview(const StepInput& in, int i, double time, double ahead, const GaSettings& settings) {
    PreviewTarget target;
    target.position = in.task.target_position(std::min(time, horizon(in)));
    target.orientation = in.ref.orientation;
    arm_.set_scene(in.scene, ahead);
    PreviewPopulation& population = populations_[i];
    int generations = settings.generations;
    if (!population.initialised()) {
      if (i > 0 && populations_[i - 1].initialised())
        population.copy_from(populations_[i - 1]);
      else
        population.randomise(arm_.box(), rng_, settings.population);
      generations = std::max(generations, int(std::lround(p(kWarmup))));
    }
    return population.evolve(arm_, target, rng_, settings, generations);
  }

  // The trajectory ends at the task's duration; a preview beyond it sees the end point.
  static double horizon(const StepInput& in) { return in.task.duration(); }

  // Offline plan for p = ∞ (allocates once): GA candidates at every knot,
  // then Viterbi over them for the largest Σ ¹S with reachable steps.
  int plan(const StepInput& in, const GaSettings& settings) {
    const double interval = p(kPlanInterval), end = std::max(horizon(in), in.state.t);
    const int knots = int(std::ceil((end - in.state.t) / interval - 1e-9)) + 1;
    const int candidates = std::clamp(settings.population, 2, kMaxPopulation);
    const int generations = std::max(settings.generations, int(std::lround(p(kWarmup))));
    Eigen::MatrixXd genes(n_, knots * candidates);
    Eigen::MatrixXd value(candidates, knots);
    Eigen::MatrixXi from(candidates, knots);
    std::vector<double> amsip(knots * candidates);
    plan_times_.resize(knots);
    int evaluations = 0;
    plan_population_.randomise(arm_.box(), rng_, candidates);
    for (int k = 0; k < knots; ++k) {
      const double time = std::min(in.state.t + k * interval, end);
      plan_times_[k] = time;
      PreviewTarget target;
      target.position = in.task.target_position(time);
      target.orientation = in.ref.orientation;
      arm_.set_scene(in.scene, time - in.state.t);
      evaluations += plan_population_.evolve(arm_, target, rng_, settings, k == 0 ? 2 * generations : generations);
      for (int c = 0; c < candidates; ++c) {
        genes.col(k * candidates + c) = plan_population_.genes().col(c);
        amsip[k * candidates + c] = arm_.score(genes.col(k * candidates + c), target).fitness;
      }
    }
    // the plan starts from the arm's own configuration (the paper's
    // reachability from the initial configuration): knot 0 has one candidate, q(t)
    {
      PreviewTarget start;
      start.position = in.task.target_position(plan_times_[0]);
      start.orientation = in.ref.orientation;
      arm_.set_scene(in.scene, 0.0);
      genes.col(0) = in.state.q;
      amsip[0] = arm_.score(genes.col(0), start).amsip;
    }
    const JointBox& box = arm_.box();
    auto excess = [&](int k, int a, int b) {  // how far a step from candidate a (knot k−1) to b (knot k) is out of reach
      double worst = 0;
      const double dt = plan_times_[k] - plan_times_[k - 1];
      for (int j = 0; j < n_; ++j) {
        const double limit = std::isfinite(limit_speed(j)) ? limit_speed(j) : kPlanJointSpeed;
        const double d = std::abs(box.difference(j, genes(j, (k - 1) * candidates + a), genes(j, k * candidates + b)));
        worst = std::max(worst, d - limit * dt);
      }
      return std::max(worst, 0.0);
    };
    for (int c = 0; c < candidates; ++c) value(c, 0) = c == 0 ? amsip[0] : -std::numeric_limits<double>::infinity();
    for (int k = 1; k < knots; ++k)
      for (int b = 0; b < candidates; ++b) {
        double best = -std::numeric_limits<double>::infinity();
        int arg = 0;
        for (int a = 0; a < candidates; ++a) {
          const double v = value(a, k - 1) - kUnreachablePenalty * excess(k, a, b);
          if (v > best) best = v, arg = a;
        }
        value(b, k) = best + amsip[k * candidates + b];
        from(b, k) = arg;
      }
    plan_.resize(n_, knots);
    int c = 0;
    value.col(knots - 1).maxCoeff(&c);
    for (int k = knots - 1; k >= 0; --k) {
      plan_.col(k) = genes.col(k * candidates + c);
      if (k > 0) c = from(c, k);
    }
    // unwrap circular joints along the plan so that interpolation is continuous
    for (int k = 1; k < knots; ++k)
      for (int j = 0; j < n_; ++j)
        plan_(j, k) = plan_(j, k - 1) + box.difference(j, plan_(j, k - 1), plan_(j, k));
    return evaluations;
  }

  double limit_speed(int joint) const { return velocity_limits_[joint]; }

  // q*(t): linear between knots, held after the last
  void plan_at(double time, Eigen::VectorXd& q) const {
    const int knots = int(plan_.cols());
    if (knots == 0) return;
    if (time <= plan_times_.front()) { q = plan_.col(0); return; }
    if (time >= plan_times_.back()) { q = plan_.col(knots - 1); return; }
    const auto it = std::upper_bound(plan_times_.begin(), plan_times_.end(), time);
    const int k = int(it - plan_times_.begin());
    const double s = (time - plan_times_[k - 1]) / (plan_times_[k] - plan_times_[k - 1]);
    q = (1 - s) * plan_.col(k - 1) + s * plan_.col(k);
  }

  // circular joints: the representative of q̃ nearest to q
  void unwrap_near(const Eigen::VectorXd& q, Eigen::VectorXd& qt) const {
    for (int j = 0; j < n_; ++j)
      if (circular_[j]) qt[j] = q[j] + std::remainder(qt[j] - q[j], 2.0 * M_PI);
  }

  void report(const StepInput& in, StepOutput& out, int previews, int evaluations) {
    // the actual arm: AMSI, AMSIP and its avoidance manipulability ellipses
    const double amsi = actual_.compute(in.model, in.kin, in.task_jacobian);
    const double potential = obstacle_potential(in.distances, p(kPotentialWidth), p(kPotentialHeight));
    out.diag.values[amsi_] = amsi;
    out.diag.values[amsip_] = amsi + potential;
    out.diag.values[potential_] = potential;
    for (int i = 0; i < kMaxPreviews; ++i) out.diag.values[preview_diag_[i]] = i < previews ? preview_s_[i] : 0.0;
    out.diag.values[evaluations_] = evaluations;
    out.diag.values[gap_] = (target_ - in.state.q).norm();
    out.diag.values[null_speed_] = null_v_.norm();
    if (int(out.overlays.ellipses.size()) != actual_.point_count())
      out.overlays.ellipses.resize(actual_.point_count());
    for (int i = 0; i < actual_.point_count(); ++i) {
      const AvoidanceEllipsoid& e = actual_.ellipsoid(i);
      OverlayEllipse& drawn = out.overlays.ellipses[i];
      drawn.centre = e.centre;
      drawn.axes.setZero();
      for (int k = 0; k < actual_.rows(); ++k) drawn.axes.col(k) = e.sigma[k] * e.directions.col(k);
    }
  }

  void on_param_changed(ParamSlot changed) override {
    // a new path-planning request (previews set to 0 again, a new knot spacing or
    // potential) replans from the arm's configuration at that step
    if (changed == kPreviews || changed == kPlanInterval || changed == kPotentialWidth || changed == kPotentialHeight)
      plan_.resize(n_, 0);
  }

  int n_;
  ImaginaryManipulator arm_;
  AvoidanceManipulability actual_;
  std::vector<PreviewPopulation> populations_;
  PreviewPopulation plan_population_;
  Rng rng_;
  RightInverse inverse_;
  Eigen::VectorXd target_, v_, null_v_, plan_q_, plan_next_, velocity_limits_;
  std::vector<Eigen::VectorXd> previews_;
  std::vector<double> preview_s_;
  std::vector<bool> circular_;
  Eigen::MatrixXd plan_;
  std::vector<double> plan_times_;
  int amsi_, amsip_, potential_, preview_diag_[kMaxPreviews], evaluations_, gap_, null_speed_;
};

}  // namespace

std::vector<ParamSpec> multi_preview_params() {
  return {
      {"previews", "Previews p", "", "number of future optimal configurations (eq. 24: 1, eq. 25: 2–3); 0 = path planning (p = ∞, planned offline before the first step)", 3, 0, kMaxPreviews, 1, {}},
      {"preview_time", "Preview time t̃", "s", "spacing of the preview times t_i* = t + i·t̃", 5.0, 0.01, 100.0, 0.1, {}},
      {"k1", "Weight k1", "", "weight of q̃_d(t + t̃) in eq. 25 (the used k_i are normalised to sum 1)", 0.3, 0.0, 1.0, 0.01, {}},
      {"k2", "Weight k2", "", "weight of q̃_d(t + 2t̃) in eq. 25", 0.65, 0.0, 1.0, 0.01, {}},
      {"k3", "Weight k3", "", "weight of q̃_d(t + 3t̃) in eq. 25", 0.05, 0.0, 1.0, 0.01, {}},
      {"kv", "Gain K_v", "1/s", "null-space gain toward the previewed configurations (K_v = kv·I)", 1.0, 0.0, 100.0, 0.1, {}},
      {"population", "GA population", "", "individuals per preview (rounded)", 20, 2, kMaxPopulation, 1, {}},
      {"generations", "GA generations per step", "", "generations of the 1-step GA each control step (rounded)", 1, 0, 50, 1, {}},
      {"mutation", "GA mutation σ", "rad", "standard deviation of a gene's Gaussian mutation", 0.1, 0.0, 3.0, 0.01, {}},
      {"potential_width", "Potential width", "m", "width of the potential band U around each obstacle", 0.3, 0.001, 10.0, 0.01, {}},
      {"potential_height", "Potential height", "", "depth of U at an obstacle surface, per link", 10.0, 0.0, 1e6, 0.1, {}},
      {"warmup_generations", "GA warm-up generations", "", "generations when a population starts (first step, planning knots)", 40, 0, 1000, 1, {}},
      {"plan_interval", "Plan knot spacing", "s", "previews = 0: time between planned configurations", 0.5, 0.01, 100.0, 0.1, {}},
  };
}
std::unique_ptr<Method> make_multi_preview(const MethodContext& ctx) { return std::make_unique<MultiPreview>(ctx); }

}  // namespace rrlab

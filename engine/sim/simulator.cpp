#include <rrlab/sim/simulator.hpp>

#include <chrono>
#include <cmath>
#include <limits>
#include <utility>

#include <rrlab/methods/registry.hpp>

namespace rrlab {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

double joint_limit_margin(const JointLimits& limits, const Eigen::VectorXd& q) {
  double margin = kInf;
  for (Eigen::Index i = 0; i < q.size(); ++i)
    margin = std::min({margin, q[i] - limits.lower[i], limits.upper[i] - q[i]});
  return margin;
}

// max_i |v_i| / bound_i over joints with a finite bound (0 when none).
double max_ratio(const Eigen::VectorXd& v, const Eigen::VectorXd& bound) {
  double r = 0;
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (std::isfinite(bound[i])) r = std::max(r, std::abs(v[i]) / bound[i]);
  return r;
}
}  // namespace

Simulator::Simulator(const Scenario& scenario) : Simulator(scenario, scenario.method.name) {
  for (const auto& [name, value] : scenario_.method.params) method_->set_param(name, value);
}

Simulator::Simulator(const Scenario& scenario, const std::string& method_name)
    : Simulator(scenario, method_name, nullptr) {}

Simulator::Simulator(const Scenario& scenario, const std::string& method_name, MethodFactory factory)
    : scenario_(scenario),
      scene_(scenario.scene),
      kin_(scenario.model),
      jacobian_(task_rows(scenario.task.space), scenario.model.dof()),
      conditioning_(task_rows(scenario.task.space), scenario.model.dof()),
      collision_(scenario.model, scenario.scene),
      self_collision_(scenario.model),
      ref_(scenario.task.space),
      total_steps_(scenario.steps()) {
  distances_.resize(scenario_.model.link_count(), int(scene_.obstacles.size()));
  if (factory) external_name_ = method_name, external_ = std::move(factory);
  install_method(method_name);
  reset_state();
}

Simulator::~Simulator() = default;

void Simulator::install_method(const std::string& name) {
  const MethodContext context{scenario_.model, scenario_.task.space, int(scene_.obstacles.size()), scenario_.seed,
                              scenario_.witness};
  if (external_ && name == external_name_) {
    method_ = external_(context);
  } else {
    const MethodInfo* info = find_method(name);
    if (!info) throw ParamError("method", "unknown method \"" + name + "\" (known: " + method_names() + ")");
    method_ = info->make(context);
  }
  method_name_ = name;
  const int n = scenario_.model.dof();
  out_.qdot = Eigen::VectorXd::Zero(n);
  out_.q_next = Eigen::VectorXd::Zero(n);
  out_.diag.names = method_->diagnostic_names();
  out_.diag.values = Eigen::VectorXd::Zero(Eigen::Index(out_.diag.names.size()));
  frame_.diagnostics = out_.diag.values;
}

void Simulator::reset() {
  renew_method();
  reset_state();
}

void Simulator::reset_state() {
  const int n = scenario_.model.dof();
  state_.t = 0;
  state_.step = 0;
  state_.q = scenario_.q0;
  state_.qdot = Eigen::VectorXd::Zero(n);
  qdot_prev_ = Eigen::VectorXd::Zero(n);
  qddot_ = Eigen::VectorXd::Zero(n);
  scene_.advance_to(0.0);
  collision_.sync(scene_, false);
  forward_kinematics(scenario_.model, state_.q, kin_);
  task_ = std::make_unique<Task>(scenario_.task, kin_.end_effector(), scenario_.duration, scenario_.dt);
  frame_ = Frame{};
  frame_.q = state_.q;
  frame_.qdot = state_.qdot;
  frame_.diagnostics = out_.diag.values;
  // Before the first step the frame shows the start as it is (end-effector,
  // target, distances), so a paused new run draws and reads right; nothing is
  // accumulated into the summary and step() evaluates again from scratch.
  evaluate(0.0);
  frame_metrics();
  collided_ = self_collided_ = limit_violated_ = false;
  min_distance_ = min_self_distance_ = kInf;
  min_margin_ = kInf;
  max_error_ = max_condition_ = max_qdot_ratio_ = max_qddot_ratio_ = 0;
  nonfinite_steps_ = position_limit_steps_ = velocity_limit_steps_ = 0;
  smoothness_.restart(state_.q, scenario_.dt);
  step_times_.clear();
}

void Simulator::set_param(const std::string& name, double value) { method_->set_param(name, value); }

void Simulator::switch_method(const std::string& name) {
  const Eigen::VectorXd keep_qdot = qdot_prev_;
  install_method(name);
  qdot_prev_ = keep_qdot;
}

void Simulator::scene_changed(bool reshape) {
  if (reshape && distances_.obstacles != int(scene_.obstacles.size())) {
    distances_.resize(scenario_.model.link_count(), int(scene_.obstacles.size()));
    // methods size their workspace by the obstacle count
    renew_method();
  }
  collision_.sync(scene_, reshape);
}

// A new instance of the current method with the same parameter values: its
// internal state (warm starts, GA population, latches) starts over.
void Simulator::renew_method() {
  const Eigen::VectorXd values = method_->param_values();
  const std::vector<ParamSpec> specs = method_->specs();
  switch_method(method_name_);
  for (size_t i = 0; i < specs.size(); ++i) method_->set_param(specs[i].name, values[Eigen::Index(i)]);
}

void Simulator::evaluate(double t) {
  scene_.advance_to(t);
  collision_.sync(scene_, false);
  forward_kinematics(scenario_.model, state_.q, kin_);
  rrlab::task_jacobian(scenario_.model, kin_, scenario_.task.space, jacobian_);
  collision_.compute(kin_, distances_);
  self_collision_.compute(kin_, self_distances_);
  task_->reference(t, kin_.end_effector(), ref_);
}

void Simulator::step() {
  const double dt = scenario_.dt;
  state_.t = double(state_.step) * dt;  // no accumulated rounding
  evaluate(state_.t);

  const StepInput in{scenario_.model, state_, ref_, scene_, dt, kin_, jacobian_, distances_, *task_, self_distances_};
  out_.integrated = false;
  method_->step(in, out_);
  if (!out_.qdot.allFinite() || (out_.integrated && !out_.q_next.allFinite())) {
    out_.qdot.setZero();  // a failing method holds the arm rather than poisoning the run
    out_.integrated = false;
    ++nonfinite_steps_;
  }

  // frame of this step: state at t, and what the method commanded
  frame_.step = state_.step;
  frame_.t = state_.t;
  frame_.q = state_.q;
  if (out_.integrated)
    frame_.qdot = (out_.q_next - state_.q) / dt;
  else
    frame_.qdot = out_.qdot;
  frame_.diagnostics = out_.diag.values;
  // a method sizes its overlay lists once (their capacity): the frame's copy
  // takes that capacity too, so a list that grows later does not allocate
  frame_.overlays.segments.reserve(out_.overlays.segments.capacity());
  frame_.overlays.points.reserve(out_.overlays.points.capacity());
  frame_.overlays = out_.overlays;
  accumulate_metrics();

  // integrate
  if (out_.integrated)
    state_.q = out_.q_next;
  else
    state_.q.noalias() += dt * out_.qdot;
  smoothness_.add(state_.q);  // the state reached, however the method got there
  // limits after integration: where the step ended and how fast it got there
  // (a method may command within its bounds and still land past them)
  if (joint_limit_margin(scenario_.model.limits, state_.q) < 0) ++position_limit_steps_;
  if (qdot_ratio_ > 1) ++velocity_limit_steps_;
  qdot_prev_ = frame_.qdot;
  state_.qdot = frame_.qdot;
  ++state_.step;
  state_.t = double(state_.step) * dt;
  task_->advance();
}

void Simulator::frame_metrics() {
  const Model& model = scenario_.model;
  const Eigen::Isometry3d& ee = kin_.end_effector();
  frame_.ee_position = ee.translation();
  frame_.ee_orientation = Eigen::Quaterniond(ee.linear());
  frame_.target = ref_.position;
  if (scenario_.task.space == TaskSpace::pose) frame_.target_orientation = Eigen::Quaterniond(ref_.orientation);
  frame_.task_error = ref_.position_error;
  frame_.orientation_error = ref_.orientation_error;
  frame_.min_distance = distances_.min_distance;
  frame_.min_distance_link = distances_.min_link;
  frame_.collided = distances_.min_distance <= 0;
  const SelfPairDistance* self = self_distances_.nearest();
  frame_.min_self_distance = self_distances_.min_distance;
  frame_.self_link_a = self ? self->pair.a : -1;
  frame_.self_link_b = self ? self->pair.b : -1;
  frame_.self_collided = self_distances_.min_distance <= 0;
  frame_.joint_limit_margin = joint_limit_margin(model.limits, state_.q);
  conditioning_.compute(jacobian_);
  frame_.manipulability = conditioning_.manipulability();
  frame_.condition_number = conditioning_.condition_number();
}

void Simulator::accumulate_metrics() {
  const Model& model = scenario_.model;
  frame_metrics();
  qddot_ = (frame_.qdot - qdot_prev_) / scenario_.dt;  // the arm starts at rest
  collided_ = collided_ || frame_.collided;
  self_collided_ = self_collided_ || frame_.self_collided;
  min_self_distance_ = std::min(min_self_distance_, frame_.min_self_distance);
  limit_violated_ = limit_violated_ || frame_.joint_limit_margin < 0;
  min_distance_ = std::min(min_distance_, frame_.min_distance);
  min_margin_ = std::min(min_margin_, frame_.joint_limit_margin);
  max_error_ = std::max(max_error_, frame_.task_error);
  max_condition_ = std::max(max_condition_, frame_.condition_number);
  qdot_ratio_ = max_ratio(frame_.qdot, model.limits.velocity);  // frame_.qdot: the velocity the step applies
  max_qdot_ratio_ = std::max(max_qdot_ratio_, qdot_ratio_);
  max_qddot_ratio_ = std::max(max_qddot_ratio_, max_ratio(qddot_, model.limits.acceleration));
}

void Simulator::note_step_time(double us) {
  frame_.step_us = us;
  step_times_.add(us);
}

Summary Simulator::summary() const {
  Summary s;
  s.scenario = scenario_.name;
  s.method = method_name_;
  s.steps = state_.step;
  s.obstacle_collided = collided_;
  s.self_collided = self_collided_;
  s.collided = collided_ || self_collided_;
  s.min_distance = min_distance_;
  if (!scenario_.model.self_pairs.empty()) s.min_self_distance = min_self_distance_;
  s.max_tracking_error = max_error_;
  s.joint_limit_violated = limit_violated_;
  s.min_joint_limit_margin = min_margin_;
  if (scenario_.model.limits.has_velocity()) s.max_qdot_ratio = max_qdot_ratio_;
  s.position_limit_steps = position_limit_steps_;
  if (scenario_.model.limits.has_velocity()) s.velocity_limit_steps = velocity_limit_steps_;
  if (scenario_.model.limits.has_acceleration()) s.max_qddot_ratio = max_qddot_ratio_;
  s.max_condition_number = max_condition_;
  s.nonfinite_steps = nonfinite_steps_;
  s.smoothness = smoothness_.stats();
  s.final_q = state_.q;
  s.step_us = step_times_.stats();
  // final state: error against the reference at the final time
  // its own kinematics: kin_ stays that of the last frame (the server draws frames with it)
  KinematicsData final_kin(scenario_.model);
  forward_kinematics(scenario_.model, state_.q, final_kin);
  TaskRef final_ref(scenario_.task.space);
  task_->reference(state_.t, final_kin.end_effector(), final_ref);
  s.final_tracking_error = final_ref.position_error;
  const double final_margin = joint_limit_margin(scenario_.model.limits, state_.q);
  s.joint_limit_violated = s.joint_limit_violated || final_margin < 0;
  s.min_joint_limit_margin = std::min(s.min_joint_limit_margin, final_margin);
  return s;
}

void timed_step(Simulator& sim) {
  const auto start = std::chrono::steady_clock::now();
  sim.step();
  const auto stop = std::chrono::steady_clock::now();
  sim.note_step_time(std::chrono::duration<double, std::micro>(stop - start).count());
}

Summary run_to_end(Simulator& sim, Recorder* recorder, const std::atomic<bool>* stop) {
  if (recorder) recorder->begin(sim);
  while (!sim.done()) {
    if (stop && stop->load(std::memory_order_relaxed)) throw RunInterrupted();
    timed_step(sim);
    if (recorder) recorder->frame(sim.frame());
  }
  Summary summary = sim.summary();
  if (recorder) recorder->end(summary);
  return summary;
}

}  // namespace rrlab

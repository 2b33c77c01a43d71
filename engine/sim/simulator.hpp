// Fixed-step, deterministic simulation of one method on one scenario.
// A step: obstacles to time t → kinematics → distances (to obstacles, and
// between links for self-collision) → task reference →
// method → metrics → integration (Euler, unless the method integrated itself).
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

#include <rrlab/collision/collision_world.hpp>
#include <rrlab/collision/self_collision.hpp>
#include <rrlab/kinematics/kinematics.hpp>
#include <rrlab/methods/method.hpp>
#include <rrlab/scenario/scenario.hpp>
#include <rrlab/sim/frame.hpp>
#include <rrlab/sim/joint_smoothness.hpp>
#include <rrlab/sim/recorder.hpp>
#include <rrlab/sim/step_time_histogram.hpp>
#include <rrlab/task/task.hpp>

namespace rrlab {

// Builds a method that is not in the registry (one written in Python).
using MethodFactory = std::function<std::unique_ptr<Method>(const MethodContext&)>;

class Simulator {
 public:
  // Uses the scenario's method and parameters (throws ParamError / ScenarioError).
  explicit Simulator(const Scenario& scenario);
  Simulator(const Scenario& scenario, const std::string& method_name);
  // A method from outside the registry, called `method_name`: `factory` builds
  // it again whenever the run starts over (reset, obstacles added).
  Simulator(const Scenario& scenario, const std::string& method_name, MethodFactory factory);
  ~Simulator();

  // Advance one step; the frame of the step just taken is frame().
  void step();
  bool done() const { return state_.step >= total_steps_; }
  long total_steps() const { return total_steps_; }
  long nonfinite_steps() const { return nonfinite_steps_; }  // steps whose method output was not finite
  void set_total_steps(long steps) { total_steps_ = steps; }
  const Frame& frame() const { return frame_; }
  // Compute time of the last step, measured by the caller (not deterministic).
  void note_step_time(double us);

  // Run inputs, applied before the next step.
  void set_param(const std::string& name, double value);
  void switch_method(const std::string& name);  // starts from the current state
  Scene& scene() { return scene_; }
  const Scene& scene() const { return scene_; }
  void scene_changed(bool reshape);  // after obstacles moved (false) or were resized/added/removed (true)
  Task& task() { return *task_; }
  const Task& task() const { return *task_; }
  void reset();  // back to q0 at t = 0: the same method and parameters, its state anew

  const Scenario& scenario() const { return scenario_; }
  const Model& model() const { return scenario_.model; }
  const State& state() const { return state_; }
  const Method& method() const { return *method_; }
  const std::string& method_name() const { return method_name_; }
  const KinematicsData& kinematics() const { return kin_; }
  const DistanceTable& distances() const { return distances_; }
  const SelfDistanceTable& self_distances() const { return self_distances_; }
  const TaskRef& reference() const { return ref_; }
  const Eigen::MatrixXd& task_jacobian() const { return jacobian_; }
  const std::vector<std::string>& diagnostic_names() const { return method_->diagnostic_names(); }

  // Summary of the steps so far, with the final tracking error at the current state.
  Summary summary() const;

 private:
  void install_method(const std::string& name);
  void renew_method();
  void reset_state();
  void evaluate(double t);  // kinematics, Jacobian, distances and reference at state_.q
  void frame_metrics();       // this frame's metrics from the evaluated state
  void accumulate_metrics();  // frame_metrics() and the run's extremes

  Scenario scenario_;
  Scene scene_;
  std::unique_ptr<Task> task_;
  std::unique_ptr<Method> method_;
  std::string method_name_;
  std::string external_name_;  // the method `external_` builds, if any
  MethodFactory external_;
  KinematicsData kin_;
  Eigen::MatrixXd jacobian_;
  JacobianConditioning conditioning_;
  CollisionWorld collision_;
  DistanceTable distances_;
  SelfCollisionWorld self_collision_;
  SelfDistanceTable self_distances_;
  TaskRef ref_;
  State state_;
  StepOutput out_;
  Frame frame_;
  Eigen::VectorXd qdot_prev_, qddot_;
  long total_steps_;

  // running summary
  bool collided_ = false, self_collided_ = false, limit_violated_ = false;
  double min_self_distance_ = 0;
  double min_distance_, max_error_ = 0, min_margin_, max_condition_ = 0;
  double max_qdot_ratio_ = 0, max_qddot_ratio_ = 0, qdot_ratio_ = 0;
  long nonfinite_steps_ = 0;
  long position_limit_steps_ = 0, velocity_limit_steps_ = 0;
  JointSmoothnessMeter smoothness_;  // of the states reached since the start or the last reset
  StepTimeHistogram step_times_;
};

// One step, its compute time noted (wall clock: kept apart from the deterministic frame).
void timed_step(Simulator& sim);

// A run left before its end because `stop` was set (a sweep stopping, a
// server exiting): nothing of it is a result.
class RunInterrupted : public std::runtime_error {
 public:
  RunInterrupted() : std::runtime_error("the run was stopped before its end") {}
};

// Runs to the end, timing each step, feeding a recorder (may be null).
// `stop` (may be null) is read between steps: once set, throws RunInterrupted.
Summary run_to_end(Simulator& sim, Recorder* recorder, const std::atomic<bool>* stop = nullptr);

}  // namespace rrlab

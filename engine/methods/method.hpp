// A redundancy-resolution method: a name, parameter specs and a step function
// that writes joint velocities (or a next configuration) into a preallocated
// output. Specs drive the UI, REST validation and the CLI alike.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <utility>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <rrlab/collision/collision_world.hpp>
#include <rrlab/collision/scene.hpp>
#include <rrlab/collision/self_collision.hpp>
#include <rrlab/kinematics/kinematics.hpp>
#include <rrlab/model/model.hpp>
#include <rrlab/task/task.hpp>
#include <rrlab/task/witness.hpp>

namespace rrlab {

struct ParamSpec {
  std::string name, label, unit, help;
  double def = 0, min = 0, max = 0, step = 0;
  std::vector<std::string> choices;  // non-empty: an enumeration; the value is the index
};

// A parameter name or value a method rejects; the message names it.
class ParamError : public std::runtime_error {
 public:
  ParamError(std::string param, const std::string& message)
      : std::runtime_error(message), param_(std::move(param)) {}
  const std::string& param() const { return param_; }

 private:
  std::string param_;
};

// Named scalars a method reports every step; names are fixed at construction.
struct Diagnostics {
  std::vector<std::string> names;
  Eigen::VectorXd values;
  int add(std::string name);  // at construction only; returns the index
  void clear() { values.setZero(); }
};

struct State {
  double t = 0;
  long step = 0;
  Eigen::VectorXd q, qdot;  // qdot: the velocity applied at the previous step
};

// Everything a method sees in one step. The simulator has already computed the
// kinematics at state.q, the task Jacobian, every link–obstacle distance and
// every self pair's distance (Model::self_pairs).
struct StepInput {
  const Model& model;
  const State& state;
  const TaskRef& ref;
  const Scene& scene;
  double dt;
  const KinematicsData& kin;
  const Eigen::MatrixXd& task_jacobian;  // rows of ref.space
  const DistanceTable& distances;
  const Task& task;  // the reference at other times (previews, RK4 stages)
  const SelfDistanceTable& self_distances;  // one row per Model::self_pairs entry
};

// Geometry a method wants drawn over the scene (dashboard overlays). Sized at
// construction or on the first step so that steady-state steps reuse storage.
struct OverlayEllipse {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Zero();  // columns: semi-axes (direction × length)
};
struct Overlays {
  std::vector<Eigen::VectorXd> ghosts;  // configurations of imaginary manipulators (joint space)
  std::vector<OverlayEllipse> ellipses;
  std::vector<Eigen::Vector3d> points;  // e.g. control points, Voronoi-boundary points
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> segments;
  bool empty() const { return ghosts.empty() && ellipses.empty() && points.empty() && segments.empty(); }
};

struct StepOutput {
  Eigen::VectorXd qdot;  // joint velocity to apply over [t, t + dt]
  // A method that integrates itself (e.g. RK4) sets this and q_next.
  bool integrated = false;
  Eigen::VectorXd q_next;
  Diagnostics diag;
  Overlays overlays;
};

// What a method may size its workspace by.
struct MethodContext {
  const Model& model;
  TaskSpace space;
  int obstacle_count;
  std::uint64_t seed = 1;  // the scenario's seed: the only source of randomness
  std::shared_ptr<const WitnessTrajectory> witness;  // the scenario's, if it has one
};

// A parameter of a method, found by its name in the method's spec list when
// the method is built. A name the list lacks throws std::logic_error, and every
// method is built by the tests: code and spec list cannot disagree on a
// position.
struct ParamSlot {
  int index = -1;
  bool operator==(const ParamSlot&) const = default;
};

class Method {
 public:
  virtual ~Method() = default;
  virtual void step(const StepInput& in, StepOutput& out) = 0;

  // Validates against the specs (range, enumeration) and throws ParamError.
  void set_param(std::string_view name, double value);
  double param(std::string_view name) const;
  const std::vector<ParamSpec>& specs() const { return specs_; }
  const Eigen::VectorXd& param_values() const { return values_; }
  // Names of the diagnostics this method reports (declared at construction).
  const std::vector<std::string>& diagnostic_names() const { return diag_names_; }

 protected:
  explicit Method(std::vector<ParamSpec> specs);
  // The parameter called `name` (std::logic_error if the spec list has none).
  ParamSlot slot(std::string_view name) const;
  // The value of enumeration `choice`'s label (std::logic_error if it has none).
  int label(ParamSlot choice, std::string_view label) const;
  double p(ParamSlot s) const { return values_[s.index]; }
  int choice(ParamSlot s) const { return static_cast<int>(values_[s.index]); }
  int declare_diagnostic(std::string name);
  // Called after a parameter changed (recompute cached values).
  virtual void on_param_changed(ParamSlot /*changed*/) {}

 private:
  std::vector<ParamSpec> specs_;
  Eigen::VectorXd values_;
  std::vector<std::string> diag_names_;
};

// Index of a parameter by name in a spec list (-1 if absent).
int find_param(const std::vector<ParamSpec>& specs, std::string_view name);
// Checks a value against a spec; returns an empty string or the problem.
std::string param_problem(const ParamSpec& spec, double value);
// An enumeration label to its index (-1 when unknown).
int choice_index(const ParamSpec& spec, std::string_view label);

}  // namespace rrlab

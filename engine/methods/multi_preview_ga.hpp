// Zhang et al. future optimal configurations: an imaginary manipulator
// with its hand on a future trajectory point, scored by AMSIP (eq. 22), and
// the 1-step genetic algorithm (Minami's real-time GA, the paper's ref. [7])
// that searches its redundancy for the best one. One population per preview,
// kept from step to step (warm start); every step it is re-scored at the new
// target and evolved a few generations. Allocation-free after construction,
// except when the obstacles' geometry changes.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <vector>

#include <rrlab/collision/collision_world.hpp>
#include <rrlab/collision/planar_obstacles.hpp>
#include <rrlab/collision/scene.hpp>
#include <rrlab/methods/multi_preview_avoidance.hpp>
#include <rrlab/methods/multi_preview_planar.hpp>
#include <rrlab/task/task.hpp>
#include <rrlab/util/right_inverse.hpp>
#include <rrlab/util/rng.hpp>

namespace rrlab {

struct PreviewTarget {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Matrix3d orientation = Eigen::Matrix3d::Identity();  // pose tasks only
};

// The box the GA samples joints in: position limits where given, else
// [−π, π] for revolute joints (then treated as circular) and ±reach for
// prismatic ones.
struct JointBox {
  Eigen::VectorXd lower, upper;
  std::vector<bool> circular;
  explicit JointBox(const Model& model);
  void confine(Eigen::Ref<Eigen::VectorXd> q) const;  // wrap circular joints, clamp the others
  // b − a, the short way round for circular joints
  double difference(int joint, double a, double b) const;
};

struct Evaluation {
  double fitness = 0;   // AMSIP minus a penalty for a hand that misses its target
  double amsip = 0;     // ¹S = ¹E + U (eq. 22)
  double amsi = 0;      // ¹E (eq. 21)
  double potential = 0; // U
  double residual = 0;  // hand error after the projection (m, rad)
};

class ImaginaryManipulator {
 public:
  ImaginaryManipulator(const Model& model, TaskSpace space);
  ~ImaginaryManipulator();

  // Obstacles as they will be `ahead` seconds after the scene's current poses
  // (constant velocity). Rebuilds the collision geometry when it changed.
  void set_scene(const Scene& scene, double ahead);
  void set_potential(double width, double height) { width_ = width, height_ = height; }

  // Moves q onto the hand target (damped Newton steps, Lamarckian: q is
  // updated), then scores it.
  Evaluation evaluate(Eigen::Ref<Eigen::VectorXd> q, const PreviewTarget& target);
  // Scores q as it is (no projection).
  Evaluation score(const Eigen::VectorXd& q, const PreviewTarget& target);

  const JointBox& box() const { return box_; }
  long evaluations() const { return evaluations_; }

 private:
  void kinematics();  // at q_: the closed form's for a planar arm, else kin_
  double hand_error(const PreviewTarget& target);  // at the last kinematics(): fills error_, returns its norm
  Evaluation score_current(const PreviewTarget& target);  // at kin_ (forward kinematics done)
  static std::uint64_t geometry_fingerprint(const Scene& scene);

  Model model_;  // a copy: the evaluator outlives no one but may outlive the caller's reference
  TaskSpace space_;
  JointBox box_;
  KinematicsData kin_;
  Eigen::MatrixXd hand_jacobian_;
  RightInverse newton_;
  Eigen::VectorXd error_, step_, q_;
  AvoidanceManipulability avoidance_;
  std::unique_ptr<PlanarArm> planar_;  // the closed-form path of planar chains, else null
  std::vector<int> ranks_;             // generic rank of each link point's avoidance matrix
  PlanarObstacles planar_obstacles_;   // the obstacles in the plane of a planar arm
  bool planar_obstacles_built_ = false, planar_obstacles_placed_ = false;
  Scene scene_;
  std::unique_ptr<CollisionWorld> collision_;
  std::uint64_t fingerprint_ = 0;
  DistanceTable distances_;
  double width_ = 0.2, height_ = 10.0;
  long evaluations_ = 0;
};

struct GaSettings {
  int population = 20;
  int generations = 1;
  double mutation = 0.1;  // standard deviation of a gene's Gaussian mutation, rad (m)
};

class PreviewPopulation {
 public:
  PreviewPopulation(int dof, int max_population);

  bool initialised() const { return size_ > 0; }
  void randomise(const JointBox& box, Rng& rng, int population);
  void copy_from(const PreviewPopulation& other);
  // Re-scores every individual at the target, then runs `generations`
  // generations: tournament selection, blend crossover, Gaussian mutation,
  // one random immigrant, (μ+λ) survival. Returns the evaluations spent.
  int evolve(ImaginaryManipulator& arm, const PreviewTarget& target, Rng& rng, const GaSettings& settings,
             int generations);

  const Eigen::VectorXd& best() const { return best_; }
  const Evaluation& best_evaluation() const { return best_eval_; }
  int size() const { return size_; }
  const Eigen::MatrixXd& genes() const { return genes_; }  // columns 0..size()-1, best first after evolve

 private:
  void resize(const JointBox& box, Rng& rng, int population);
  int tournament(Rng& rng) const;
  void survive();

  int n_, max_, size_ = 0;
  Eigen::MatrixXd genes_, scratch_;  // n x 2·max: parents | children
  std::vector<Evaluation> evals_, scratch_evals_;
  std::vector<int> order_;
  Eigen::VectorXd best_;
  Evaluation best_eval_;
};

}  // namespace rrlab

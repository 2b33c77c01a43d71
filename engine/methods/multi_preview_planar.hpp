// The GA's imaginary manipulator for a planar chain (revolute joints about z,
// links along their +x, an xy hand task): the same projection and AMSI as
// the general code (multi_preview_ga.cpp, multi_preview_avoidance.cpp), in
// closed form on stack scalars — forward kinematics from cumulative angles,
// a 2 x 2 damped Newton solve, the hand's 2 x 2 pseudoinverse and the link
// points' 2 x 2 M Mᵀ. The numbers agree with the general path to rounding
// (tests/engine/methods/multi_preview_planar_test.cpp); the general path
// takes ~2.5 µs per evaluation on Zhang's 4-link arm, this one a fraction.
#pragma once

#include <Eigen/Core>
#include <vector>

#include <rrlab/kinematics/kinematics.hpp>
#include <rrlab/model/model.hpp>

namespace rrlab {

class PlanarArm {
 public:
  // True for a planar model this class computes exactly: every joint
  // revolute about z with no fixed rotation, every link a capsule ending at
  // its own joint's frame, the base a translation in the plane.
  static bool applies(const Model& model, TaskSpace space);
  explicit PlanarArm(const Model& model);

  // Joint positions p_0 (base) .. p_n (hand) at q.
  void kinematics(const Eigen::Ref<const Eigen::VectorXd>& q);
  // Hand error target − hand (after kinematics()); returns its norm.
  double hand_error(const Eigen::Vector3d& target);
  // One damped Newton step δq = Jᵀ(JJᵀ + λ²I)⁻¹ e on the last hand_error.
  void newton_step(double damping, Eigen::Ref<Eigen::VectorXd> dq) const;
  // AMSI ¹E (Zhang eq. 21) at the last kinematics(): Σ c_r √e_r(¹M_i ¹M_iᵀ)
  // over the link points i = 1..n−1 with their generic ranks `ranks`.
  double amsi(const std::vector<int>& ranks);
  // The links' segments into kin (the collision world reads only those for capsules).
  void write_links(KinematicsData& kin) const;
  const std::vector<Eigen::Vector2d>& joints() const { return p_; }  // p_0 .. p_n at the last kinematics()
  const std::vector<double>& radii() const { return radius_; }       // each link's capsule radius

 private:
  int n_;
  Eigen::Vector2d base_;
  std::vector<double> length_, radius_;
  std::vector<Eigen::Vector2d> p_;   // p_0 .. p_n
  Eigen::Vector2d error_ = Eigen::Vector2d::Zero();
  double ball_[4] = {};
};

}  // namespace rrlab

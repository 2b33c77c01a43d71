// Chen et al. (2002) §4: the per-link criteria of the posture generation rule,
// as small pure functions (the method is posture_generation.cpp).
#pragma once

#include <Eigen/Core>

namespace rrlab::chen {

// An orientation cone (eq. 18): the value Γ = √(1 − s²), s = (cos Ψ − cos φ)/(1 − cos φ)
// for an included angle Ψ < φ (else Γ = 1, inactive), and its slope dΓ/dΨ.
// Eq. 19 as printed is not the derivative of eq. 18 (it has the opposite sign
// and √(1 − s²) where the derivative has 1/√(1 − s²)); the exact derivative is
// used, which grows as Ψ shrinks, as the text says, and stays finite at Ψ = 0:
//   dΓ/dΨ = s·√2·cos(Ψ/2) / (√(1 − cos φ)·√(1 + s)).
// Ψ <= 0 (a joint past its limit) counts as Ψ = 0.
struct Cone {
  bool active = false;
  double value = 1;    // Γ
  double slope = 0;    // dΓ/dΨ
  double closeness = 0;  // cos Ψ, the γ1 term of eq. 30
};
Cone cone(double psi, double phi);

// Included angle Ψ between u = −O_i and b (eq. 18) and dΨ/dθ for a rotation
// of u by du = d(−O_i)/dθ (if u points straight at b: −|du|, a push either way).
struct Angle {
  double psi = 0, dpsi = 0;
};
Angle included_angle(const Eigen::Vector3d& u, const Eigen::Vector3d& du, const Eigen::Vector3d& b);

// Eq. 21–22: adjacent-link distance term for the estimated distance vector
// D̄ = −O_i − D_ik (eq. 20) and du = d(−O_i)/dθ.
struct Adjacent {
  bool active = false;
  double value = 1, grad = 0, closeness = 0;  // closeness: cos(‖D̄‖π/(2η)) of eq. 30
};
Adjacent adjacent_term(const Eigen::Vector3d& dbar, const Eigen::Vector3d& du, double eta);

// Eq. 28: Γ4 = O_i·E_i/(‖O_i‖‖E_i‖) and its derivative for dO = d(O_i)/dθ.
struct Elastic {
  double value = 0, grad = 0;
};
Elastic elastic_term(const Eigen::Vector3d& o, const Eigen::Vector3d& d_o, const Eigen::Vector3d& e);

}  // namespace rrlab::chen

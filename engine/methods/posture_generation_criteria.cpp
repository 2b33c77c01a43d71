#include <rrlab/methods/posture_generation_criteria.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace rrlab::chen {

Cone cone(double psi, double phi) {
  Cone c;
  if (psi >= phi) return c;
  psi = std::max(psi, 0.0);
  const double cos_phi = std::cos(phi);
  const double s = (std::cos(psi) - cos_phi) / (1 - cos_phi);
  c.active = true;
  c.value = std::sqrt(std::max(0.0, 1 - s * s));  // eq. 18
  c.slope = s * std::sqrt(2.0) * std::cos(0.5 * psi) / (std::sqrt(1 - cos_phi) * std::sqrt(1 + s));
  c.closeness = std::cos(psi);
  return c;
}

Angle included_angle(const Eigen::Vector3d& u, const Eigen::Vector3d& du, const Eigen::Vector3d& b) {
  Angle a;
  const double nu = u.norm(), nb = b.norm();
  if (nu == 0 || nb == 0) return a;
  const Eigen::Vector3d uh = u / nu, bh = b / nb;
  const double sin_psi = uh.cross(bh).norm();
  a.psi = std::atan2(sin_psi, uh.dot(bh));
  if (sin_psi > 1e-9)
    a.dpsi = -(du.dot(bh) / nu) / sin_psi;  // dΨ/dθ = −(dc/dθ)/sin Ψ
  else
    a.dpsi = -du.norm() / nu;
  return a;
}

Adjacent adjacent_term(const Eigen::Vector3d& dbar, const Eigen::Vector3d& du, double eta) {
  Adjacent a;
  const double len = dbar.norm();
  if (len > eta) return a;
  const double x = len / eta * M_PI / 2;
  a.active = true;
  a.value = 2 * eta / M_PI * std::sin(x);                               // eq. 21
  a.grad = len > 0 ? du.dot(dbar / len) * std::cos(x) : du.norm();    // eq. 22
  a.closeness = std::cos(x);
  return a;
}

Elastic elastic_term(const Eigen::Vector3d& o, const Eigen::Vector3d& d_o, const Eigen::Vector3d& e) {
  Elastic r;
  const double no = o.norm(), ne = e.norm();
  if (no == 0 || ne == 0) return r;
  r.value = o.dot(e) / (no * ne);  // eq. 28 (the length of O_i is constant under rotation)
  r.grad = d_o.dot(e) / (no * ne);
  return r;
}

}  // namespace rrlab::chen

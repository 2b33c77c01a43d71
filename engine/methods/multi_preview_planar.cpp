#include <rrlab/methods/multi_preview_planar.hpp>

#include <algorithm>
#include <cmath>

#include <rrlab/methods/multi_preview_avoidance.hpp>

namespace rrlab {

namespace {
constexpr double kPinvTolerance = 1e-12;  // RightInverse::factor_pinv's default: σ² below it x σ²max is dropped
}

bool PlanarArm::applies(const Model& model, TaskSpace space) {
  if (space != TaskSpace::xy || !model.base.linear().isIdentity(0) || model.base.translation().z() != 0) return false;
  if (model.link_count() != model.dof() || model.dof() == 0 || model.dof() > 64) return false;
  for (int j = 0; j < model.dof(); ++j) {
    const Joint& joint = model.joints[j];
    if (joint.type != JointType::revolute || joint.axis != Eigen::Vector3d::UnitZ()) return false;
    if (!joint.pre.matrix().isIdentity(0) || !joint.post.linear().isIdentity(0)) return false;
    if (joint.post.translation().y() != 0 || joint.post.translation().z() != 0) return false;
    if (model.links[j].last_joint != j || model.links[j].mesh) return false;
  }
  return true;
}

PlanarArm::PlanarArm(const Model& model)
    : n_(model.dof()), base_(model.base.translation().head<2>()), p_(model.dof() + 1, Eigen::Vector2d::Zero()) {
  for (const Joint& joint : model.joints) length_.push_back(joint.post.translation().x());
  for (const Link& link : model.links) radius_.push_back(link.radius);
  for (int r = 0; r < 4; ++r) ball_[r] = unit_ball_volume(r);
}

void PlanarArm::kinematics(const Eigen::Ref<const Eigen::VectorXd>& q) {
  // rotations about z compose by adding angles: link j points along φ_j = q_1 + … + q_j
  double angle = 0;
  p_[0] = base_;
  for (int j = 0; j < n_; ++j) {
    angle += q[j];
    double s, c;
    ::sincos(angle, &s, &c);
    p_[j + 1] = p_[j] + length_[j] * Eigen::Vector2d(c, s);
  }
}

double PlanarArm::hand_error(const Eigen::Vector3d& target) {
  error_ = target.head<2>() - p_[n_];
  return error_.norm();
}

void PlanarArm::newton_step(double damping, Eigen::Ref<Eigen::VectorXd> dq) const {
  // J's column j: e_z × (p_n − p_j) = (−(y_n − y_j), x_n − x_j)
  const Eigen::Vector2d hand = p_[n_];
  double a = 0, b = 0, c = 0;
  for (int j = 0; j < n_; ++j) {
    const double jx = -(hand.y() - p_[j].y()), jy = hand.x() - p_[j].x();
    a += jx * jx, b += jx * jy, c += jy * jy;
  }
  a += damping * damping, c += damping * damping;
  const double det = a * c - b * b;
  const double y0 = (c * error_.x() - b * error_.y()) / det, y1 = (a * error_.y() - b * error_.x()) / det;
  for (int j = 0; j < n_; ++j) dq[j] = -(hand.y() - p_[j].y()) * y0 + (hand.x() - p_[j].x()) * y1;
}

double PlanarArm::amsi(const std::vector<int>& ranks) {
  const Eigen::Vector2d hand = p_[n_];
  double jx[64], jy[64];  // the hand Jacobian's rows (n ≤ 64: Model's limit for masks elsewhere)
  double a = 0, b = 0, c = 0;
  for (int j = 0; j < n_; ++j) {
    jx[j] = -(hand.y() - p_[j].y()), jy[j] = hand.x() - p_[j].x();
    a += jx[j] * jx[j], b += jx[j] * jy[j], c += jy[j] * jy[j];
  }
  // (J Jᵀ)⁺ with factor_pinv's rule: eigenvalues below 1e-12 of the largest count as 0
  const double half_trace = 0.5 * (a + c), radius = std::sqrt(0.25 * (a - c) * (a - c) + b * b);
  const double top = std::max(half_trace + radius, 0.0), bottom = half_trace - radius;
  const double floor = kPinvTolerance * top;
  double p00 = 0, p01 = 0, p11 = 0;
  if (top > floor && top > 0) {
    if (bottom > floor && bottom > 0) {
      const double det = a * c - b * b;
      p00 = c / det, p01 = -b / det, p11 = a / det;
    } else {  // rank 1: u uᵀ / λ_max, u the top eigenvector
      Eigen::Vector2d u = std::abs(top - a) > std::abs(top - c) ? Eigen::Vector2d(b, top - a) : Eigen::Vector2d(top - c, b);
      if (u.squaredNorm() == 0) u = a >= c ? Eigen::Vector2d(1, 0) : Eigen::Vector2d(0, 1);
      u.normalize();
      p00 = u.x() * u.x() / top, p01 = u.x() * u.y() / top, p11 = u.y() * u.y() / top;
    }
  }
  double total = 0;
  for (int i = 0; i + 1 < n_; ++i) {
    // ¹M_i's rows: J_i's two rows z_r (point p_{i+1}, joints 0..i) projected
    // onto the hand's null space, z_r − Jᵀ (J Jᵀ)⁺ J z_r (Zhang eq. 5); one
    // pass for w_r = J z_r, one for the projected rows' products (M Mᵀ)
    const Eigen::Vector2d point = p_[i + 1];
    double w00 = 0, w01 = 0, w10 = 0, w11 = 0;  // w_r = (w_r0, w_r1)
    for (int j = 0; j <= i; ++j) {
      const double z0 = -(point.y() - p_[j].y()), z1 = point.x() - p_[j].x();
      w00 += jx[j] * z0, w01 += jy[j] * z0, w10 += jx[j] * z1, w11 += jy[j] * z1;
    }
    const double y00 = p00 * w00 + p01 * w01, y01 = p01 * w00 + p11 * w01;  // y_r = (J Jᵀ)⁺ w_r
    const double y10 = p00 * w10 + p01 * w11, y11 = p01 * w10 + p11 * w11;
    double m00 = 0, m01 = 0, m11 = 0;
    for (int j = 0; j < n_; ++j) {
      const double z0 = j > i ? 0.0 : -(point.y() - p_[j].y()), z1 = j > i ? 0.0 : point.x() - p_[j].x();
      const double r0 = z0 - (jx[j] * y00 + jy[j] * y01), r1 = z1 - (jx[j] * y10 + jy[j] * y11);
      m00 += r0 * r0, m01 += r0 * r1, m11 += r1 * r1;
    }
    // Zhang eq. 18, 20 over the generic rank (see AvoidanceManipulability::compute_volumes)
    const int rank = ranks[size_t(i)];
    const double product = rank == 1 ? m00 + m11 : rank == 2 ? m00 * m11 - m01 * m01 : 0.0;
    total += rank > 0 ? ball_[rank] * std::sqrt(std::max(product, 0.0)) : 0.0;
  }
  return total;
}

void PlanarArm::write_links(KinematicsData& kin) const {
  for (int l = 0; l < n_; ++l) {
    kin.link_start.col(l) = Eigen::Vector3d(p_[l].x(), p_[l].y(), 0);
    kin.link_end.col(l) = Eigen::Vector3d(p_[l + 1].x(), p_[l + 1].y(), 0);
  }
}

}  // namespace rrlab

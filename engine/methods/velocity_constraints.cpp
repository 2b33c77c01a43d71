// Joint limits as velocity bounds and velocity dampers on obstacle and self
// pairs, shared by qp_ik, hqp and diffik (velocity_constraints.hpp).
//
// Box, per joint i (the same merge order as qp_constraints):
//   position:  γ (q_min − q)/dt ≤ q̇ ≤ γ (q_max − q)/dt, 1e-9 rad inside the limit; with
//              an acceleration limit also the braking velocity v: v²/(2a) + 1.5 v dt ≤ q_max − q
//   velocity:  |q̇| ≤ q̇_max
//   step cap:  |q̇_i| dt R_i ≤ max_step (R_i: the farthest capsule point moved by joint i)
//   acceleration: |q̇ − q̇_prev| ≤ a dt
// When two of them leave nothing in common, the later one wins (acceleration
// over the rest, velocity over position): the box is never empty.
//
// Velocity damper (Faverjon & Tournassoud 1987, "A local based approach for
// path planning of manipulators with a high number of degrees of freedom"),
// for a pair at distance d < d_i:
//   ḋ ≥ −ξ (d − d_s)/(d_i − d_s)
// with ḋ = nᵀ(J_p q̇ − v_o) for a link point p and an obstacle moving at v_o
// (n: unit normal obstacle → link), and ḋ = nᵀ(J_a(p_a) − J_b(p_b)) q̇ for a
// self pair (n: b → a). Discretely d − d_s shrinks by at most a factor
// 1 − ξ dt/(d_i − d_s) per step, so the rate ξ/(d_i − d_s) is capped at 1/dt
// (the linearised step never jumps past d_s). Inside d_s the row asks the
// pair to separate. Against an obstacle with faces (box, polygon, wall, mesh)
// the link's two ends get rows too, measured to the tangent plane at the
// nearest point (a link nearly parallel to a face has two near points and the
// nearest one jumps between them). A row no joint can change (the base link
// against a fixed obstacle) is left out: it could only make the set empty.
#include <rrlab/methods/velocity_constraints.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rrlab {
namespace {

constexpr double kNoBound = std::numeric_limits<double>::infinity();
constexpr double kBoundShrink = 1.0 - 1e-9;  // a ratio to a limit never rounds above 1
constexpr double kLimitMargin = 1e-9;        // rad (m): the position bound stays this far inside
constexpr double kViolationRegularisation = 1e-6;  // ε of the least-violation QP

// braking_velocity where acceleration is limited and there is room; else no bound
double braking_velocity_towards(double room, double acc, double dt) {
  if (room <= 0 || !std::isfinite(acc)) return kNoBound;
  return braking_velocity(room, acc, dt);
}

// [lo, hi] ∩ [a, b]; when empty, the point of [a, b] nearest to [lo, hi] wins:
// the later bound ([a, b]) is kept.
void merge_bounds(double& lo, double& hi, double a, double b) {
  if (b < lo) {
    lo = hi = b;
  } else if (a > hi) {
    lo = hi = a;
  } else {
    lo = std::max(lo, a);
    hi = std::min(hi, b);
  }
}

}  // namespace

VelocityConstraintBuilder::VelocityConstraintBuilder(const Model& model, int obstacle_count)
    : n_(model.dof()), point_jacobian_(3, model.dof()), other_jacobian_(3, model.dof()), reach_(model.dof()) {
  resize(model, obstacle_count);
}

void VelocityConstraintBuilder::resize(const Model& model, int obstacle_count) {
  capacity_ = std::max(1, 3 * model.link_count() * std::max(obstacle_count, 0) + int(model.self_pairs.size()));
}

bool VelocityConstraintBuilder::needs_resize(const StepInput& in) const {
  return 3 * in.distances.links * in.distances.obstacles + int(in.self_distances.pairs.size()) > capacity_;
}

void VelocityConstraintBuilder::size(VelocityConstraints& out) const {
  out.lower.resize(n_);
  out.upper.resize(n_);
  out.A.setZero(capacity_, n_);
  out.b.setZero(capacity_);
  out.pairs.resize(size_t(capacity_));
  out.rows = 0;
}

void VelocityConstraintBuilder::build(const StepInput& in, const LimitSettings& limits,
                                      const DamperSettings& dampers, VelocityConstraints& out) {
  joint_bounds(in, limits, out);
  out.rows = 0;
  obstacle_rows(in, dampers, out);
  if (dampers.self_pairs) self_rows(in, dampers, out);
}

double braking_velocity(double room, double acc, double dt) {
  const double b = 1.5 * dt;
  return acc * (-b + std::sqrt(b * b + 2.0 * room / acc));  // root of v²/(2a) + b v = room
}

void joint_reach(const Model& model, const KinematicsData& kin, Eigen::VectorXd& reach) {
  reach.setZero();
  for (int i = 0; i < model.dof(); ++i) {
    if (model.joints[i].type == JointType::prismatic) {
      reach[i] = 1.0;
      continue;
    }
    const Eigen::Vector3d axis_point = kin.axis_points.col(i), axis = kin.axis_dirs.col(i);
    for (int l = 0; l < model.link_count(); ++l) {
      if (model.links[l].last_joint < i) continue;
      const double r0 = axis.cross(Eigen::Vector3d(kin.link_start.col(l)) - axis_point).norm();
      const double r1 = axis.cross(Eigen::Vector3d(kin.link_end.col(l)) - axis_point).norm();
      reach[i] = std::max(reach[i], std::max(r0, r1) + model.links[l].radius);
    }
  }
}

void VelocityConstraintBuilder::joint_bounds(const StepInput& in, const LimitSettings& limits,
                                             VelocityConstraints& out) {
  const JointLimits& lim = in.model.limits;
  const double dt = in.dt, gamma = limits.position_gain;
  if (limits.max_step > 0) joint_reach(in.model, in.kin, reach_);
  for (int i = 0; i < n_; ++i) {
    const double q = in.state.q[i], acc = lim.acceleration[i];
    double range_lo = -kNoBound, range_hi = kNoBound;
    if (std::isfinite(lim.upper[i])) {  // γ (q_max − q)/dt, and braking in time
      const double room = lim.upper[i] - q - kLimitMargin;
      range_hi = std::min(gamma * room / dt, braking_velocity_towards(room, acc, dt));
    }
    if (std::isfinite(lim.lower[i])) {
      const double room = q - lim.lower[i] - kLimitMargin;
      range_lo = -std::min(gamma * room / dt, braking_velocity_towards(room, acc, dt));
    }
    double lo = range_lo, hi = range_hi;
    if (!(lo <= hi)) lo = hi = 0.5 * (lo + hi);  // a range narrower than the margins: hold the middle
    merge_bounds(lo, hi, -kBoundShrink * lim.velocity[i], kBoundShrink * lim.velocity[i]);
    if (limits.max_step > 0 && reach_[i] > 1e-12) {
      const double cap = kBoundShrink * limits.max_step / (dt * reach_[i]);
      merge_bounds(lo, hi, -cap, cap);
    }
    if (std::isfinite(acc)) {
      const double previous = in.state.qdot[i];
      merge_bounds(lo, hi, previous - kBoundShrink * dt * acc, previous + kBoundShrink * dt * acc);
    }
    out.lower[i] = lo;
    out.upper[i] = hi;
  }
}

// Faverjon & Tournassoud: ḋ ≥ −ξ (d − d_s)/(d_i − d_s); the row's Jacobian
// part (A.row(rows)) is already written, the obstacle's own rate added by the caller.
void VelocityConstraintBuilder::add_row(const StepInput& in, const DamperSettings& dampers, double distance,
                                        VelocityConstraints& out) {
  const double rate = std::min(dampers.gain / (dampers.detection - dampers.safety), 1.0 / in.dt);
  out.b[out.rows] = -rate * (distance - dampers.safety);
  out.pairs[size_t(out.rows)].distance = distance;
  ++out.rows;
}

void VelocityConstraintBuilder::obstacle_rows(const StepInput& in, const DamperSettings& dampers,
                                              VelocityConstraints& out) {
  const DistanceTable& table = in.distances;
  for (int link = 0; link < table.links; ++link) {
    const double radius = in.model.links[link].radius;
    for (int o = 0; o < table.obstacles; ++o) {
      const LinkObstacleDistance& pair = table.at(link, o);
      if (!(pair.distance < dampers.detection) || !pair.normal.allFinite()) continue;
      const Obstacle& obstacle = in.scene.obstacles[size_t(o)];
      const double v_along = pair.normal.dot(obstacle.velocity);
      const Eigen::Vector3d points[3] = {pair.on_link, in.kin.link_start.col(link), in.kin.link_end.col(link)};
      for (int e = 0; e < (has_faces(obstacle.shape) ? 3 : 1); ++e) {
        const double d = e == 0 ? pair.distance : pair.normal.dot(points[e] - pair.on_obstacle) - radius;
        if (e > 0 && (!(d < dampers.detection) || (points[e] - pair.on_link).squaredNorm() < 1e-12)) continue;
        point_jacobian_linear(in.model, in.kin, link, points[e], point_jacobian_);
        auto row = out.A.row(out.rows);
        row.noalias() = pair.normal.transpose() * point_jacobian_;  // ḋ = nᵀ J_p q̇ − nᵀv_o
        if (row.squaredNorm() < 1e-18) continue;
        DamperPair& drawn = out.pairs[size_t(out.rows)];
        drawn.link = link;
        drawn.other = -1 - o;
        drawn.on_link = points[e];
        drawn.on_other = points[e] - (d + radius) * pair.normal;
        add_row(in, dampers, d, out);
        out.b[out.rows - 1] += v_along;
      }
    }
  }
}

void VelocityConstraintBuilder::self_rows(const StepInput& in, const DamperSettings& dampers,
                                          VelocityConstraints& out) {
  for (const SelfPairDistance& pair : in.self_distances.pairs) {
    if (!(pair.distance < dampers.detection) || !pair.normal.allFinite()) continue;
    point_jacobian_linear(in.model, in.kin, pair.pair.a, pair.on_a, point_jacobian_);
    point_jacobian_linear(in.model, in.kin, pair.pair.b, pair.on_b, other_jacobian_);
    point_jacobian_ -= other_jacobian_;
    auto row = out.A.row(out.rows);
    row.noalias() = pair.normal.transpose() * point_jacobian_;  // ḋ = nᵀ(J_a − J_b) q̇
    if (row.squaredNorm() < 1e-18) continue;
    DamperPair& drawn = out.pairs[size_t(out.rows)];
    drawn.link = pair.pair.a;
    drawn.other = pair.pair.b;
    drawn.on_link = pair.on_a;
    drawn.on_other = pair.on_b;
    add_row(in, dampers, pair.distance, out);
  }
}

LeastViolation::LeastViolation(int dof, int row_capacity)
    : n_(dof),
      capacity_(row_capacity),
      problem_(dof + row_capacity, 0, row_capacity),
      solver_(dof + row_capacity, 0, row_capacity),
      qdot_(Eigen::VectorXd::Zero(dof)) {
  // x = [q̇; w]: H = diag(ε I, I), rows [A I] x ≥ b, w ≥ 0
  problem_.H.topLeftCorner(n_, n_) *= kViolationRegularisation;
  problem_.A_in.rightCols(capacity_).setIdentity();
  problem_.lower.tail(capacity_).setZero();
}

bool LeastViolation::solve(const VelocityConstraints& c, Eigen::VectorXd& slack) {
  const int rows = c.rows;
  problem_.A_in.topLeftCorner(rows, n_) = c.A.topRows(rows);
  problem_.b_in.head(rows) = c.b.head(rows);
  problem_.ineq_count = rows;
  problem_.lower.head(n_) = c.lower;
  problem_.upper.head(n_) = c.upper;
  problem_.upper.tail(capacity_).setZero();  // unused rows: no slack
  problem_.upper.segment(n_, rows).setConstant(kNoBound);
  const QpStatus status = solver_.solve(problem_);
  if (status == QpStatus::optimal) {
    qdot_ = solver_.x().head(n_);
  } else {
    qdot_ = c.lower.cwiseMax(c.upper.cwiseMin(Eigen::VectorXd::Zero(n_)));
  }
  // w* = what the rows lack at q̇*, never negative
  slack.head(rows).noalias() = c.A.topRows(rows) * qdot_;
  slack.head(rows) = (c.b.head(rows) - slack.head(rows)).cwiseMax(0.0);
  return status == QpStatus::optimal;
}

int draw_active_dampers(const QpSolver& solver, int first_row, const VelocityConstraints& constraints,
                        std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& segments) {
  segments.clear();
  int active = 0;
  for (int k = 0; k < constraints.rows; ++k) {
    if (!solver.inequality_active(first_row + k)) continue;
    ++active;
    if (segments.size() < segments.capacity())
      segments.emplace_back(constraints.pairs[size_t(k)].on_link, constraints.pairs[size_t(k)].on_other);
  }
  return active;
}

}  // namespace rrlab

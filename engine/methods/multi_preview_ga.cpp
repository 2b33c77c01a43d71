#include <rrlab/methods/multi_preview_ga.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace rrlab {

namespace {
constexpr int kNewtonIterations = 8;
constexpr double kNewtonTolerance = 1e-7;  // m (rad): hand on target
constexpr double kNewtonDamping = 1e-3;    // keeps Newton steps bounded near singularities
constexpr double kMissPenalty = 100.0;     // fitness lost per metre (radian) the hand misses by
constexpr double kBlend = 0.25;            // BLX-α crossover: u ∈ [−α, 1 + α]
constexpr double kWorst = -1e300;

// (−π, π]; remainder returns an angle within [−π, π] unchanged, so it is skipped there
double wrap_angle(double a) { return std::abs(a) <= M_PI ? a : std::remainder(a, 2.0 * M_PI); }
}  // namespace

JointBox::JointBox(const Model& model) : lower(model.dof()), upper(model.dof()), circular(model.dof()) {
  for (int j = 0; j < model.dof(); ++j) {
    const bool revolute = model.joints[j].type == JointType::revolute;
    const double lo = model.limits.lower[j], hi = model.limits.upper[j];
    const bool bounded = std::isfinite(lo) && std::isfinite(hi);
    circular[j] = revolute && !bounded;
    const double span = revolute ? M_PI : model.reach();
    lower[j] = std::isfinite(lo) ? lo : -span;
    upper[j] = std::isfinite(hi) ? hi : span;
  }
}

void JointBox::confine(Eigen::Ref<Eigen::VectorXd> q) const {
  for (Eigen::Index j = 0; j < q.size(); ++j)
    q[j] = circular[j] ? wrap_angle(q[j]) : std::clamp(q[j], lower[j], upper[j]);
}

double JointBox::difference(int joint, double a, double b) const {
  return circular[joint] ? wrap_angle(b - a) : b - a;
}

ImaginaryManipulator::ImaginaryManipulator(const Model& model, TaskSpace space)
    : model_(model),
      space_(space),
      box_(model),
      kin_(model),
      hand_jacobian_(task_rows(space), model.dof()),
      newton_(task_rows(space), model.dof()),
      error_(task_rows(space)),
      step_(model.dof()),
      q_(model.dof()),
      avoidance_(model, space, false) {  // fitness needs AMSI, not the ellipsoids' directions
  if (PlanarArm::applies(model, space)) planar_ = std::make_unique<PlanarArm>(model);
  for (int i = 0; i < avoidance_.point_count(); ++i) ranks_.push_back(avoidance_.ellipsoid(i).volume_rank);
}

ImaginaryManipulator::~ImaginaryManipulator() = default;

std::uint64_t ImaginaryManipulator::geometry_fingerprint(const Scene& scene) {
  // FNV-1a over the bits of everything that shapes an obstacle (not its pose)
  std::uint64_t h = 1469598103934665603ULL;
  auto mix = [&h](double v) {
    h ^= std::bit_cast<std::uint64_t>(v);
    h *= 1099511628211ULL;
  };
  mix(double(scene.obstacles.size()));
  for (const Obstacle& o : scene.obstacles) {
    mix(double(static_cast<int>(o.shape)));
    for (const Eigen::Vector2d& p : o.points) mix(p.x()), mix(p.y());
    mix(o.z_min), mix(o.z_max), mix(o.radius);
    for (int k = 0; k < 3; ++k) mix(o.size[k]), mix(o.normal[k]);
  }
  return h;
}

void ImaginaryManipulator::set_scene(const Scene& scene, double ahead) {
  const std::uint64_t fingerprint = geometry_fingerprint(scene);
  if (!collision_ || fingerprint != fingerprint_) {
    scene_ = scene;  // new geometry: the only allocation after construction
    collision_ = std::make_unique<CollisionWorld>(model_, scene_);
    distances_.resize(model_.link_count(), int(scene_.obstacles.size()));
    fingerprint_ = fingerprint;
    planar_obstacles_built_ = planar_ && planar_obstacles_.build(scene_);
  }
  // a planar arm scores its potential in its plane where every obstacle allows
  planar_obstacles_placed_ = planar_obstacles_built_ && planar_obstacles_.place(scene, ahead);
  for (size_t k = 0; k < scene.obstacles.size(); ++k) {
    const Obstacle& now = scene.obstacles[k];
    Obstacle& later = scene_.obstacles[k];
    later.rotation = now.rotation;
    later.velocity = now.velocity;
    later.position = now.position + now.velocity * ahead;
  }
  collision_->sync(scene_, false);
}

void ImaginaryManipulator::kinematics() {
  if (planar_)
    planar_->kinematics(q_);
  else
    forward_kinematics(model_, q_, kin_);
}

double ImaginaryManipulator::hand_error(const PreviewTarget& target) {
  if (planar_) return planar_->hand_error(target.position);
  const Eigen::Isometry3d& hand = kin_.end_effector();
  const Eigen::Vector3d position_error = target.position - hand.translation();
  switch (space_) {
    case TaskSpace::xy: error_ = position_error.head<2>(); break;
    case TaskSpace::xyz: error_ = position_error; break;
    case TaskSpace::pose:
      error_.head<3>() = position_error;
      error_.tail<3>() = orientation_error(target.orientation, hand.linear());
      break;
  }
  return error_.norm();
}

Evaluation ImaginaryManipulator::evaluate(Eigen::Ref<Eigen::VectorXd> q, const PreviewTarget& target) {
  // the paper fixes the hand on r_d(t_i*) and lets the GA choose the
  // redundancy (its q1, q2 with q3, q4 "determined depending on the hand
  // position"); for any chain we get there by Newton steps from the gene
  q_ = q;
  double residual = 0;
  for (int it = 0;; ++it) {
    kinematics();
    residual = hand_error(target);
    if (residual < kNewtonTolerance || it == kNewtonIterations) break;
    if (planar_) {  // the same damped step in closed form
      planar_->newton_step(kNewtonDamping, step_);
    } else {
      task_jacobian(model_, kin_, space_, hand_jacobian_);
      newton_.factor_dls(hand_jacobian_, kNewtonDamping);
      newton_.apply(error_, step_);
    }
    q_ += step_;
    box_.confine(q_);
  }
  q = q_;
  Evaluation e = score_current(target);  // the kinematics are already at q_
  e.residual = residual;
  e.fitness = e.amsip - kMissPenalty * residual;
  if (!std::isfinite(e.fitness)) e.fitness = kWorst;
  return e;
}

Evaluation ImaginaryManipulator::score(const Eigen::VectorXd& q, const PreviewTarget& target) {
  q_ = q;
  kinematics();
  return score_current(target);
}

Evaluation ImaginaryManipulator::score_current(const PreviewTarget& target) {
  ++evaluations_;
  Evaluation e;
  e.residual = hand_error(target);
  if (planar_) {
    e.amsi = planar_->amsi(ranks_);  // eq. 21
  } else {
    task_jacobian(model_, kin_, space_, hand_jacobian_);
    e.amsi = avoidance_.compute(model_, kin_, hand_jacobian_);  // eq. 21
  }
  if (planar_obstacles_placed_) {
    e.potential = -height_ * planar_obstacles_.band_sum(planar_->joints(), planar_->radii(), width_);
  } else if (collision_) {
    if (planar_) planar_->write_links(kin_);  // the segments the collision world reads
    // U counts only pairs nearer than the band's width: the others need no exact distance
    collision_->compute_near(kin_, distances_, width_);
    e.potential = obstacle_potential(distances_, width_, height_);
  }
  e.amsip = e.amsi + e.potential;  // Zhang eq. 22: ¹S = ¹E + U
  e.fitness = e.amsip - kMissPenalty * e.residual;
  return e;
}

PreviewPopulation::PreviewPopulation(int dof, int max_population)
    : n_(dof),
      max_(max_population),
      genes_(dof, 2 * max_population),
      scratch_(dof, max_population),
      evals_(2 * max_population),
      scratch_evals_(max_population),
      order_(2 * max_population),
      best_(Eigen::VectorXd::Zero(dof)) {}

void PreviewPopulation::randomise(const JointBox& box, Rng& rng, int population) {
  size_ = std::clamp(population, 2, max_);
  for (int k = 0; k < size_; ++k)
    for (int j = 0; j < n_; ++j) genes_(j, k) = rng.uniform(box.lower[j], box.upper[j]);
  best_ = genes_.col(0);
}

void PreviewPopulation::copy_from(const PreviewPopulation& other) {
  size_ = other.size_;
  genes_.leftCols(size_) = other.genes_.leftCols(size_);
  for (int k = 0; k < size_; ++k) evals_[k] = other.evals_[k];
  best_ = other.best_;
  best_eval_ = other.best_eval_;
}

void PreviewPopulation::resize(const JointBox& box, Rng& rng, int population) {
  population = std::clamp(population, 2, max_);
  // a larger population is filled with random newcomers; a smaller one keeps
  // the best (the population is sorted after every evolve)
  for (int k = size_; k < population; ++k)
    for (int j = 0; j < n_; ++j) genes_(j, k) = rng.uniform(box.lower[j], box.upper[j]);
  size_ = population;
}

int PreviewPopulation::tournament(Rng& rng) const {
  const int a = int(rng.below(std::uint64_t(size_))), b = int(rng.below(std::uint64_t(size_)));
  return evals_[a].fitness >= evals_[b].fitness ? a : b;
}

void PreviewPopulation::survive() {
  // (μ+λ): the best `size_` of parents and children, best first
  const int total = 2 * size_;
  for (int k = 0; k < total; ++k) order_[k] = k;
  std::sort(order_.begin(), order_.begin() + total, [this](int a, int b) {
    if (evals_[a].fitness != evals_[b].fitness) return evals_[a].fitness > evals_[b].fitness;
    return a < b;
  });
  for (int k = 0; k < size_; ++k) {
    scratch_.col(k) = genes_.col(order_[k]);
    scratch_evals_[k] = evals_[order_[k]];
  }
  genes_.leftCols(size_) = scratch_.leftCols(size_);
  for (int k = 0; k < size_; ++k) evals_[k] = scratch_evals_[k];
}

int PreviewPopulation::evolve(ImaginaryManipulator& arm, const PreviewTarget& target, Rng& rng,
                              const GaSettings& settings, int generations) {
  const JointBox& box = arm.box();
  if (size_ == 0) randomise(box, rng, settings.population);
  if (settings.population != size_) resize(box, rng, settings.population);
  int evaluations = 0;
  // the target moved since the last step: re-score (and re-project) everyone
  for (int k = 0; k < size_; ++k, ++evaluations) evals_[k] = arm.evaluate(genes_.col(k), target);
  for (int g = 0; g < generations; ++g) {
    for (int c = 0; c < size_; ++c, ++evaluations) {
      auto child = genes_.col(size_ + c);
      if (c == size_ - 1) {
        // one immigrant per generation keeps other peaks of ¹S in reach (Fig. 9)
        for (int j = 0; j < n_; ++j) child[j] = rng.uniform(box.lower[j], box.upper[j]);
      } else {
        const int a = tournament(rng), b = tournament(rng);
        for (int j = 0; j < n_; ++j) {
          const double u = rng.uniform(-kBlend, 1.0 + kBlend);
          child[j] = genes_(j, a) + u * box.difference(j, genes_(j, a), genes_(j, b));
          if (rng.uniform() < 0.5) child[j] += settings.mutation * rng.normal();
        }
        box.confine(child);
      }
      evals_[size_ + c] = arm.evaluate(child, target);
    }
    survive();
  }
  if (generations == 0) {
    // still sorted by the fresh scores
    for (int k = 0; k < size_; ++k) evals_[size_ + k] = Evaluation{kWorst};
    survive();
  }
  best_ = genes_.col(0);
  best_eval_ = evals_[0];
  return evaluations;
}

}  // namespace rrlab

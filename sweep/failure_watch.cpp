#include <rrlab/sweep/failure_watch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <rrlab/sim/simulator.hpp>

namespace rrlab::sweep {

namespace {

// In the order equal times are settled.
enum Kind { kNonfinite, kCollision, kSelfCollision, kJointLimit, kJointSpeed, kTrackingLost, kStalled, kKinds };
constexpr std::array<const char*, kKinds> kNames = {"nonfinite",   "collision",   "self_collision", "joint_limit",
                                                    "joint_speed", "tracking_lost", "stalled"};
// The path time the hand is at: searched this far back from the present.
constexpr double kProgressSearch = 2.0;  // s
// Of the path's points within this of the nearest, the latest is the hand's place.
constexpr double kProgressTolerance = 1e-3;  // m

}  // namespace

FailureWatch::FailureWatch(const SuccessCriteria& criteria, Recorder* next)
    : criteria_(criteria), next_(next), first_(kKinds) {}

void FailureWatch::begin(const Simulator& sim) {
  sim_ = &sim;
  dt_ = sim.scenario().dt;
  nonfinite_seen_ = sim.nonfinite_steps();
  std::fill(first_.begin(), first_.end(), std::nullopt);
  settled_error_over_ = false;
  reference_.clear();
  progress_.clear();
  reference_.reserve(size_t(sim.total_steps()));
  progress_.reserve(size_t(sim.total_steps()));
  if (next_) next_->begin(sim);
}

void FailureWatch::note(int kind, double t) {
  if (!first_[size_t(kind)]) first_[size_t(kind)] = t;
}

void FailureWatch::frame(const Frame& f) {
  end_t_ = f.t + dt_;
  if (sim_->nonfinite_steps() > nonfinite_seen_) {
    nonfinite_seen_ = sim_->nonfinite_steps();
    if (!criteria_.nonfinite) note(kNonfinite, f.t);
  }
  if (!criteria_.collision && f.collided) note(kCollision, f.t);
  if (!criteria_.collision && f.self_collided) note(kSelfCollision, f.t);
  if (criteria_.min_distance && !(f.min_distance >= *criteria_.min_distance)) note(kCollision, f.t);
  if (criteria_.joint_limits && f.joint_limit_margin < 0) note(kJointLimit, f.t);
  if (criteria_.joint_speeds) {
    const Eigen::VectorXd& limit = sim_->scenario().model.limits.velocity;
    for (Eigen::Index i = 0; i < f.qdot.size() && i < limit.size(); ++i)
      if (std::isfinite(limit[i]) && !(std::abs(f.qdot[i]) <= limit[i] * (1 + kJointSpeedTolerance))) {
        note(kJointSpeed, f.t);
        break;
      }
  }
  if (criteria_.max_tracking_error && f.t >= criteria_.settle_time - 1e-9 &&
      !(f.task_error <= *criteria_.max_tracking_error)) {
    note(kTrackingLost, f.t);
    settled_error_over_ = true;
  }
  watch_progress(f);
  if (next_) next_->frame(f);
}

// The step of the path the hand is at: among the recent references, the
// latest within kProgressTolerance of the nearest. Progress is the furthest
// such step so far; a stall, progress that stays put for kStallWindow while
// the reference moves away from where the hand is.
void FailureWatch::watch_progress(const Frame& f) {
  reference_.push_back(f.target);
  const long k = long(reference_.size()) - 1;
  const long from = std::max(0L, k - long(std::lround(kProgressSearch / dt_)));
  double nearest = std::numeric_limits<double>::infinity();
  for (long j = from; j <= k; ++j) nearest = std::min(nearest, (reference_[size_t(j)] - f.ee_position).norm());
  long at = from;
  for (long j = k; j >= from; --j)
    if ((reference_[size_t(j)] - f.ee_position).norm() <= nearest + kProgressTolerance) {
      at = j;
      break;
    }
  progress_.push_back(std::max(at, k > 0 ? progress_.back() : 0L));
  const long window = std::max(1L, long(std::lround(kStallWindow / dt_)));
  if (k < window || first_[kStalled]) return;
  const long reached = progress_[size_t(k)];
  const bool stuck = double(reached - progress_[size_t(k - window)]) * dt_ < kStallProgress;
  const bool reference_moved = (reference_[size_t(k)] - reference_[size_t(reached)]).norm() > kStallMotion;
  if (!stuck || !reference_moved) return;
  long since = k;  // the first step at the place the hand still is
  while (since > k - window && progress_[size_t(since - 1)] == reached) --since;
  note(kStalled, double(since) * dt_);
}

void FailureWatch::end(const Summary& summary) {
  // the state after the last step, which no frame shows
  if (criteria_.joint_limits && summary.joint_limit_violated) note(kJointLimit, end_t_);
  if (criteria_.max_final_tracking_error && !(summary.final_tracking_error <= *criteria_.max_final_tracking_error))
    note(kTrackingLost, end_t_);
  if (next_) next_->end(summary);
}

bool FailureWatch::tracking_held() const { return criteria_.settle_time == 0 || !settled_error_over_; }

std::optional<FirstFailure> FailureWatch::first(bool passed) const {
  if (passed) return std::nullopt;
  std::optional<FirstFailure> first;
  for (size_t kind = 0; kind < kKinds; ++kind)
    if (first_[kind] && (!first || *first_[kind] < first->t)) first = FirstFailure{kNames[kind], *first_[kind]};
  // a verdict no frame explains (cannot happen with the criteria above): say so
  return first ? first : FirstFailure{"other", end_t_};
}

}  // namespace rrlab::sweep

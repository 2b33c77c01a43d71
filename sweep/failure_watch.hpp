// Why and when a sweep run fails: its first failure mode under the sweep's
// success criteria, watched frame by frame.
//
// Modes, each with the time it began:
// - collision: a link touches an obstacle (or comes nearer than the
//   criteria's min_distance), unless the criteria allow collisions;
// - self_collision: two links the allowed-collision matrix keeps touch,
//   unless the criteria allow collisions;
// - joint_limit: a joint past its limit, when the criteria hold limits;
// - joint_speed: a joint faster than its velocity limit, when the criteria
//   hold speeds;
// - tracking_lost: the position error past the criteria's max_tracking_error
//   from its settle_time on (or, at the end, the final error past
//   max_final_tracking_error);
// - stalled: no progress along the path for 1 s of path time (the hand stays
//   at the same place of the path while the reference moves on), dated from
//   when the progress stopped;
// - nonfinite: the method's output was not finite (the step held the arm),
//   unless the criteria allow it.
// The first by time is the run's; equal times go in the order above, with
// nonfinite first. A run the criteria pass has none.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <rrlab/sim/recorder.hpp>
#include <rrlab/sweep/success_criteria.hpp>

namespace rrlab::sweep {

struct FirstFailure {
  std::string mode;  // collision, self_collision, joint_limit, joint_speed, tracking_lost, stalled, nonfinite
  double t = 0;      // s
};

// Observes a run (as its Recorder, passing every frame on to `next`, which
// may be null) and names its first failure.
class FailureWatch final : public Recorder {
 public:
  // No progress for this long is a stall; progress means the path time the
  // hand is at advanced by more than kStallProgress.
  static constexpr double kStallWindow = 1.0;     // s
  static constexpr double kStallProgress = 0.05;  // s of path time
  static constexpr double kStallMotion = 1e-3;    // m: the reference must have moved this far meanwhile

  explicit FailureWatch(const SuccessCriteria& criteria, Recorder* next = nullptr);

  void begin(const Simulator& sim) override;
  void frame(const Frame& frame) override;
  void end(const Summary& summary) override;

  // The first failure, for a run the criteria fail (`passed` false); none
  // for one they pass. Call after end().
  std::optional<FirstFailure> first(bool passed) const;

  // The part of the verdict the summary cannot give: the tracking bound from
  // the settle time on. True without a settle time.
  bool tracking_held() const;

 private:
  void note(int kind, double t);
  void watch_progress(const Frame& frame);

  SuccessCriteria criteria_;
  Recorder* next_;
  const Simulator* sim_ = nullptr;
  double dt_ = 0, end_t_ = 0;
  bool settled_error_over_ = false;
  long nonfinite_seen_ = 0;
  std::vector<std::optional<double>> first_;  // per kind
  // path progress: the reference at every step, and the step of the path the hand is at
  std::vector<Eigen::Vector3d> reference_;
  std::vector<long> progress_;  // per step: the furthest path step reached so far
};

}  // namespace rrlab::sweep

// Obstacles that block the minimum-norm solution. pinv ignores obstacles, so
// one pinv run of a case without them is its path whatever is placed: an
// obstacle on that arm's axis at some step is one pinv runs into. A case is
// blocked by several obstacles when each is met where none of the others is
// (at another step, or by another link), so removing one leaves pinv
// colliding with the rest, and avoiding takes more than one manoeuvre.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <limits>
#include <string>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include <rrlab/collision/scene.hpp>
#include <rrlab/generators/generator_case.hpp>
#include <rrlab/generators/generator_clearance.hpp>
#include <rrlab/generators/generator_obstacles.hpp>
#include <rrlab/generators/generator_options.hpp>
#include <rrlab/generators/generator_witness.hpp>
#include <rrlab/util/rng.hpp>

namespace rrlab {

// The default of option "blocking": how many obstacles are placed on pinv's arm.
constexpr IntRange kDefaultBlocking{2, 2};

// Option "block_pinv" (default true). An _open variant (c.open) refuses it
// (and "blocking"): false.
bool read_block_pinv(const GeneratorOptions& options, const GeneratorCase& c);
// Options "blocking" (0-16, default kDefaultBlocking) and "block_pinv"
// (false: blocking 0).
IntRange read_blocking(const GeneratorOptions& options, const GeneratorCase& c);

// The arm of the minimum-norm solution (a pinv run of the case without
// obstacles) at every frame; nullopt when pinv's output was not finite.
std::optional<ArmSweep> minimum_norm_sweep(const GeneratorCase& c, const WitnessedArm& drawn, TaskSpace space);

// The capsules of `pinv` (indices, ascending) where its arm strays farthest
// from the witness arm at the same step (link midpoints): the 30 % of them
// where an obstacle on pinv's arm may stand clear of the witness.
std::vector<size_t> straying_capsules(const ArmSweep& pinv, const ArmSweep& witness);

// Where a blocking obstacle is placed: one of pinv's capsules (its step and
// link), a point on its axis, and the time of its step (s).
struct BlockAnchor {
  size_t capsule = 0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double t = 0;
};

// The blocking obstacles of a case, placed one after another on pinv's arm.
class PinvBlockers {
 public:
  // Blockers keep `clearance` from the witness arm at every step.
  PinvBlockers(const ArmSweep& pinv, const ArmSweep& witness, double clearance);

  const ArmSweep& pinv() const { return pinv_; }
  // How far an obstacle centred on `point` at time `t`, moving at `velocity`,
  // may reach from its centre and keep the clearance (its centre's least
  // distance from the witness arm's surface less the clearance: negative,
  // none fits). Exact below `enough`.
  double room(const Eigen::Vector3d& point, double t, const Eigen::Vector3d& velocity,
              double enough = std::numeric_limits<double>::infinity()) const;
  // Where a blocker whose shape always holds a ball of `inner` (m) about its
  // centre is centred: the anchor moved away from the witness arm's nearest
  // point by `inner` and half the anchor link's radius, so it still reaches
  // that far into pinv's link. Nullopt when the anchor is on the witness arm.
  std::optional<Eigen::Vector3d> centre(const BlockAnchor& anchor, const Eigen::Vector3d& velocity, double inner) const;
  // A blocker of `shape` at the anchor (moving at `velocity`): its centre
  // (centre(), for the shape at size.min) and a size (m) drawn in `size`
  // below what keeps the clearance there (shape_reach); nullopt when
  // size.min does not fit.
  struct Fit {
    Eigen::Vector3d centre;
    double size = 0;
  };
  std::optional<Fit> fit(const BlockAnchor& anchor, const Eigen::Vector3d& velocity, const std::string& shape,
                         bool spatial, Range size, Rng& rng) const;
  // A point on one of the straying capsules that no admitted obstacle meets;
  // nullopt when every one is met.
  std::optional<BlockAnchor> draw_anchor(Rng& rng) const;
  // Admits `obstacle` (scenario syntax) placed at `anchor` when it meets
  // pinv's arm there and meets no other admitted obstacle's anchor; its
  // straying capsules are then taken.
  bool admit(const nlohmann::json& obstacle, const BlockAnchor& anchor);
  const std::vector<BlockAnchor>& anchors() const { return anchors_; }

 private:
  const ArmSweep& pinv_;
  SweepRoom witness_room_;
  double clearance_;
  std::vector<size_t> free_;  // straying capsules no admitted obstacle meets
  std::vector<BlockAnchor> anchors_;
};

// An obstacle around `anchor` (the k-th placed); nullopt rejects the draw.
using BlockerDraw = std::function<std::optional<nlohmann::json>(const BlockAnchor& anchor, int k, Rng& rng)>;

// `count` blocking obstacles, the k-th the first of up to `draws` drawn
// around an anchor that keeps out of the witness arm and is admitted;
// nullopt when one found no place.
std::optional<nlohmann::json> place_blockers(int count, PinvBlockers& blockers, const KeepOut& keep_out,
                                             const BlockerDraw& draw, Rng& rng, int draws = 100);

// `count` balls, each reaching at least half a link radius into one of
// pinv's straying capsules (PinvBlockers::centre), of a radius drawn in
// `radius` below what keeps the clearance from the witness arm at every step
// and stays off the other balls' anchors (the roomiest of `candidates`
// anchors), ids "ball1", "ball2", ... Nullopt when one finds no place of
// radius.min.
std::optional<nlohmann::json> balls_on_pinv(int count, PinvBlockers& blockers, Range radius, Rng& rng,
                                            int candidates = 24);

// How many distinct obstacles the minimum-norm solution's arm meets (a link at
// distance <= 0) at some frame of a pinv run of `doc`: the Simulator that
// `rrlab run CASE --method pinv` runs, so the count is that run's.
int pinv_blocking_obstacles(const nlohmann::json& doc);

}  // namespace rrlab

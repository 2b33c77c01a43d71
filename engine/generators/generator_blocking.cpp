#include <rrlab/generators/generator_blocking.hpp>

#include <algorithm>
#include <limits>

#include <rrlab/collision/collision_world.hpp>
#include <rrlab/collision/segment_geometry.hpp>
#include <rrlab/scenario/scenario.hpp>
#include <rrlab/sim/simulator.hpp>

namespace rrlab {

namespace {

constexpr IntRange kBlockingAllowed{0, 16};
constexpr size_t kStrayingTenths = 3;  // of pinv's capsules: where blockers may be anchored

// Whether `obstacle` meets capsule `index` of `sweep` at that capsule's step.
bool meets_capsule(const ArmSweep& sweep, size_t index, const Obstacle& obstacle) {
  return capsules_met(sweep, {index}, obstacle).front();
}

}  // namespace

bool read_block_pinv(const GeneratorOptions& options, const GeneratorCase& c) {
  if (!c.open) return options.boolean("block_pinv", true);
  for (const char* key : {"blocking", "block_pinv"})
    if (options.has(key))
      throw ScenarioError(std::string("options.") + key,
                          c.family + " places no obstacle to block the minimum-norm solution; without _open it does");
  return false;
}

IntRange read_blocking(const GeneratorOptions& options, const GeneratorCase& c) {
  const bool block_pinv = read_block_pinv(options, c);
  if (!options.has("blocking")) return block_pinv ? kDefaultBlocking : IntRange{0, 0};
  const IntRange blocking = options.int_range("blocking", kDefaultBlocking, kBlockingAllowed);
  if (!block_pinv && blocking.max > 0) throw ScenarioError("options.blocking", "must be 0 with block_pinv false");
  return blocking;
}

std::optional<ArmSweep> minimum_norm_sweep(const GeneratorCase& c, const WitnessedArm& drawn, TaskSpace space) {
  Simulator sim(parse_scenario(witnessed_document(c, "", drawn, nlohmann::json::array(), space, 0.0)), "pinv");
  std::vector<Eigen::VectorXd> steps;
  steps.reserve(size_t(sim.total_steps()) + 1);
  // the configurations a run measures (frames), not the state after the last step
  while (!sim.done()) {
    sim.step();
    steps.push_back(sim.frame().q);
  }
  if (sim.summary().nonfinite_steps > 0) return std::nullopt;
  return arm_sweep(drawn.arm.model, steps, drawn.witness.step_dt);
}

std::vector<size_t> straying_capsules(const ArmSweep& pinv, const ArmSweep& witness) {
  std::vector<std::pair<double, size_t>> by_distance;
  const size_t n = std::min(pinv.capsules.size(), witness.capsules.size());
  for (size_t i = 0; i < n; ++i) {
    const CapsuleSegment &p = pinv.capsules[i], &w = witness.capsules[i];
    by_distance.emplace_back(-((p.a + p.b) - (w.a + w.b)).norm(), i);
  }
  const size_t keep = std::min(by_distance.size(), std::max<size_t>(1, by_distance.size() * kStrayingTenths / 10));
  std::partial_sort(by_distance.begin(), by_distance.begin() + long(keep), by_distance.end());
  std::vector<size_t> out;
  for (size_t i = 0; i < keep; ++i) out.push_back(by_distance[i].second);
  std::sort(out.begin(), out.end());
  return out;
}

PinvBlockers::PinvBlockers(const ArmSweep& pinv, const ArmSweep& witness, double clearance)
    : pinv_(pinv), witness_room_(witness), clearance_(clearance), free_(straying_capsules(pinv, witness)) {}

double PinvBlockers::room(const Eigen::Vector3d& point, double t, const Eigen::Vector3d& velocity, double enough) const {
  return witness_room_.at(point, t, velocity, enough + clearance_) - clearance_;
}

std::optional<Eigen::Vector3d> PinvBlockers::centre(const BlockAnchor& anchor, const Eigen::Vector3d& velocity,
                                                    double inner) const {
  Eigen::Vector3d away;
  witness_room_.at(anchor.point, anchor.t, velocity, std::numeric_limits<double>::infinity(), &away);
  if (!(away.norm() > 1e-9)) return std::nullopt;
  const double push = inner + 0.5 * pinv_.capsules[anchor.capsule].radius;
  Eigen::Vector3d c = anchor.point + push * away.normalized();
  for (int j = 0; j < 3; ++j) c[j] = rounded(c[j], kDrawStep);
  return c;
}

std::optional<PinvBlockers::Fit> PinvBlockers::fit(const BlockAnchor& anchor, const Eigen::Vector3d& velocity,
                                                   const std::string& shape, bool spatial, Range size, Rng& rng) const {
  const std::optional<Eigen::Vector3d> c = centre(anchor, velocity, shape_inner(shape) * size.min);
  if (!c) return std::nullopt;
  const double reach = shape_reach(shape, spatial);
  if (reach == 0) {  // a point: any size, its position clear (by a drawn step, for rounding)
    if (room(*c, anchor.t, velocity, 2 * kDrawStep) < kDrawStep) return std::nullopt;
    return Fit{*c, size.draw(rng)};
  }
  const double most = std::min(size.max, room(*c, anchor.t, velocity, size.max * reach) / reach);
  if (most < size.min) return std::nullopt;
  return Fit{*c, Range{size.min, most}.draw(rng)};
}

std::optional<BlockAnchor> PinvBlockers::draw_anchor(Rng& rng) const {
  if (free_.empty()) return std::nullopt;
  BlockAnchor anchor;
  anchor.capsule = free_[rng.below(free_.size())];
  const CapsuleSegment& link = pinv_.capsules[anchor.capsule];
  const double u = rng.uniform();
  anchor.point = link.a + u * (link.b - link.a);
  anchor.t = double(anchor.capsule / size_t(std::max(pinv_.links, 1))) * pinv_.dt;
  return anchor;
}

bool PinvBlockers::admit(const nlohmann::json& obstacle, const BlockAnchor& anchor) {
  Obstacle o;
  try {
    o = parse_obstacle_json(obstacle, "obstacle");
  } catch (const ScenarioError&) {
    return false;
  }
  if (!meets_capsule(pinv_, anchor.capsule, o)) return false;
  for (const BlockAnchor& other : anchors_)
    if (meets_capsule(pinv_, other.capsule, o)) return false;
  const std::vector<bool> met = capsules_met(pinv_, free_, o);
  std::vector<size_t> still_free;
  for (size_t i = 0; i < free_.size(); ++i)
    if (!met[i]) still_free.push_back(free_[i]);
  free_ = std::move(still_free);
  anchors_.push_back(anchor);
  return true;
}

std::optional<nlohmann::json> place_blockers(int count, PinvBlockers& blockers, const KeepOut& keep_out,
                                             const BlockerDraw& draw, Rng& rng, int draws) {
  std::optional<BlockAnchor> anchor;  // of the latest draw, for its admission
  return place_obstacles(
      count, keep_out,
      [&](int k, Rng& r) -> std::optional<nlohmann::json> {
        anchor = blockers.draw_anchor(r);
        if (!anchor) return std::nullopt;  // pinv's straying arm is met everywhere already
        return draw(*anchor, k, r);
      },
      rng, draws, [&](int, const nlohmann::json& o) { return blockers.admit(o, *anchor); });
}

std::optional<nlohmann::json> balls_on_pinv(int count, PinvBlockers& blockers, Range radius, Rng& rng, int candidates) {
  const ArmSweep& pinv = blockers.pinv();
  // room for a ball at c: from the witness arm, and off the other balls' anchors
  const auto room_for_ball = [&](const Eigen::Vector3d& c) {
    double least = blockers.room(c, 0, Eigen::Vector3d::Zero(), radius.max);
    for (const BlockAnchor& other : blockers.anchors()) {
      const CapsuleSegment& s = pinv.capsules[other.capsule];
      least = std::min(least, (collision::closest_point_on_segment(s.a, s.b, c) - c).norm() - s.radius);
    }
    return least;
  };
  nlohmann::json balls = nlohmann::json::array();
  for (int k = 0; k < count; ++k) {
    double best = -1;
    std::optional<BlockAnchor> best_anchor;
    Eigen::Vector3d best_centre = Eigen::Vector3d::Zero();
    for (int i = 0; i < candidates; ++i) {
      const std::optional<BlockAnchor> anchor = blockers.draw_anchor(rng);
      if (!anchor) return std::nullopt;
      const std::optional<Eigen::Vector3d> centre = blockers.centre(*anchor, Eigen::Vector3d::Zero(), radius.min);
      if (!centre) continue;
      const double room = room_for_ball(*centre);
      if (room > best) best = room, best_anchor = anchor, best_centre = *centre;
    }
    if (!best_anchor || best < radius.min) return std::nullopt;
    // drawn below the room, not as large as it allows: a smaller ball leaves
    // more of pinv's arm to the next
    const double r = rounded(Range{radius.min, std::min(best, radius.max) - 1e-4}.draw(rng), 1e-4);
    if (r < radius.min) return std::nullopt;
    const Eigen::Vector3d& c = best_centre;
    nlohmann::json ball = {{"id", "ball" + std::to_string(k + 1)},
                           {"shape", "sphere"},
                           {"center", {c.x(), c.y(), c.z()}},
                           {"radius", r}};
    if (!blockers.admit(ball, *best_anchor)) return std::nullopt;
    balls.push_back(std::move(ball));
  }
  return balls;
}

int pinv_blocking_obstacles(const nlohmann::json& doc) {
  Simulator sim(parse_scenario(doc), "pinv");
  std::vector<bool> met(sim.scene().obstacles.size(), false);
  while (!sim.done()) {
    sim.step();
    const DistanceTable& d = sim.distances();
    for (int l = 0; l < d.links; ++l)
      for (int o = 0; o < d.obstacles; ++o)
        if (d.at(l, o).distance <= 0) met[size_t(o)] = true;
  }
  return int(std::count(met.begin(), met.end(), true));
}

}  // namespace rrlab

// Family narrow_passage: a planar arm whose hand's path threads a gap between
// two walls (boxes standing across the hand's trace), cut to the witness.
//
// | option         | meaning                                              | default                      | unit    |
// |----------------|------------------------------------------------------|------------------------------|---------|
// | dof            | joints (links) of the arm, [min, max] or a number    | [3, 12]                      | —       |
// | link_length    | each link's length, drawn per link                   | [0.2, 0.6]                   | m       |
// | link_radius    | every link's capsule radius                          | 0.02                         | m       |
// | gap_width      | free width between the walls: cases outside are redrawn | [4, 20] × link_radius     | m       |
// | wall_length    | each wall's length across the path (at most)         | [0.2, 0.4]                   | × reach |
// | wall_thickness | each wall's thickness along the path                 | [0.03, 0.08]                 | × reach |
// | clearance      | least distance of a wall from the witness arm        | 0.05                         | m       |
// | block_pinv     | keep only walls the arm of pinv runs into            | true                         | —       |
// | waypoints      | waypoints after the start                            | [1, 3]                       | —       |
// | speed          | hand speed the witness is timed by                     | 0.2 × reach per second       | m/s     |
// | dt             | time step                                            | 0.01                         | s       |
// | time_law       | "quintic" (rest to rest per segment) or "linear"     | quintic                      | —       |
//
// The walls stand square to the hand's trace at a point of 0.2-0.8 of it. The
// gap is the witness's own: every link capsule of the witness arm, over the
// whole run, that passes through the walls' strip (grown by its radius and the
// clearance) marks an interval across the trace; the walls begin where the
// interval around the hand ends, and stop before any other. So the witness
// passes with the clearance, and the gap is as narrow as the witness allows;
// each wall comes within two clearances of the witness arm, so both bound it.
// With block_pinv the minimum-norm solution's arm (a pinv run) must hit a wall.
#include <algorithm>
#include <cmath>

#include <rrlab/generators/generator_arms.hpp>
#include <rrlab/generators/generator_blocking.hpp>
#include <rrlab/generators/generator_case.hpp>
#include <rrlab/generators/generator_clutter.hpp>
#include <rrlab/generators/generator_obstacles.hpp>
#include <rrlab/generators/generator_witness.hpp>
#include <rrlab/scenario/scenario.hpp>

namespace rrlab {

namespace {

constexpr int kWallDraws = 20;
constexpr double kWallAtFrom = 0.2, kWallAtTo = 0.8;  // fraction of the hand's samples
constexpr double kShortestWall = 0.25;              // of the drawn length: shorter walls are redrawn
// each wall comes within 2 clearances (and 1 mm, for the walls' rounding) of the witness arm
constexpr double kWallsBound = 2, kWallsRounding = 1e-3;

struct Passage {
  nlohmann::json walls;
  double gap = 0, thickness = 0;
};

struct Interval {
  double lo, hi;
};

// The intervals across the trace (u) that capsules passing through the strip
// |v| <= half_width cover, each grown by its radius and the clearance, merged;
// only those that reach into |u| < reach_out (the farthest a gap and a wall can
// extend: beyond, none can change a passage).
std::vector<Interval> covered(const ArmSweep& sweep, const Eigen::Vector3d& at, const Eigen::Vector3d& along,
                              const Eigen::Vector3d& across, double half_width, double clearance, double reach_out) {
  std::vector<Interval> out;
  for (const CapsuleSegment& c : sweep.capsules) {
    const double grow = c.radius + clearance;
    const double va = (c.a - at).dot(along), vb = (c.b - at).dot(along);
    const double ua = (c.a - at).dot(across), ub = (c.b - at).dot(across);
    const double limit = half_width + grow;
    // the part of the segment inside |v| <= limit
    double s0 = 0, s1 = 1;
    if (va == vb) {
      if (std::abs(va) > limit) continue;
    } else {
      double t0 = (-limit - va) / (vb - va), t1 = (limit - va) / (vb - va);
      if (t0 > t1) std::swap(t0, t1);
      s0 = std::max(s0, t0);
      s1 = std::min(s1, t1);
      if (s0 > s1) continue;
    }
    const double u0 = ua + s0 * (ub - ua), u1 = ua + s1 * (ub - ua);
    const Interval i{std::min(u0, u1) - grow, std::max(u0, u1) + grow};
    if (i.hi > -reach_out && i.lo < reach_out) out.push_back(i);
  }
  std::sort(out.begin(), out.end(), [](const Interval& a, const Interval& b) { return a.lo < b.lo; });
  std::vector<Interval> merged;
  for (const Interval& i : out) {
    if (!merged.empty() && i.lo <= merged.back().hi)
      merged.back().hi = std::max(merged.back().hi, i.hi);
    else
      merged.push_back(i);
  }
  return merged;
}

nlohmann::json wall(const char* id, const Eigen::Vector3d& at, const Eigen::Vector3d& across, double from,
                    double to, double thickness, double yaw) {
  const Eigen::Vector3d center = at + 0.5 * (from + to) * across;
  return {{"id", id},
          {"shape", "box"},
          {"center", {rounded(center.x()), rounded(center.y())}},
          {"size", {thickness, rounded(to - from)}},
          {"rpy", {0, 0, yaw}}};
}

// Walls across the trace at hand sample j, or nullopt when the witness leaves
// no gap there within the options.
std::optional<Passage> passage_at(const WitnessedArm& drawn, size_t j, double length, double thickness,
                                  double clearance, const Range& gap_width) {
  const std::vector<Eigen::Vector3d>& hand = drawn.witness.hand;
  const Eigen::Vector3d direction = hand[j + 1] - hand[j - 1];
  if (direction.norm() < 1e-9) return std::nullopt;  // the hand rests here
  const Eigen::Vector3d along = direction.normalized(), across(-along.y(), along.x(), 0);
  const Eigen::Vector3d at = hand[j];
  // a gap wider than gap_width.max is refused, and a wall ends at most
  // `length` beyond the gap: intervals farther out cannot matter
  const double reach_out = gap_width.max + length + 1.0;
  const std::vector<Interval> intervals =
      covered(drawn.sweep, at, along, across, 0.5 * thickness, clearance, reach_out);
  const auto around = std::find_if(intervals.begin(), intervals.end(),
                                   [](const Interval& i) { return i.lo <= 0 && 0 <= i.hi; });
  if (around == intervals.end()) return std::nullopt;
  Passage p;
  p.gap = around->hi - around->lo;
  p.thickness = thickness;
  if (p.gap < gap_width.min || p.gap > gap_width.max) return std::nullopt;
  // each wall runs from the gap to the drawn length or the next covered interval
  const double left_end = around + 1 != intervals.end() ? std::min(around->hi + length, (around + 1)->lo)
                                                        : around->hi + length;
  const double right_end = around != intervals.begin() ? std::max(around->lo - length, (around - 1)->hi)
                                                       : around->lo - length;
  if (left_end - around->hi < kShortestWall * length || around->lo - right_end < kShortestWall * length)
    return std::nullopt;
  const double yaw = rounded(std::atan2(along.y(), along.x()));
  // a little inside the free stretch: rounding the centre must not bring a wall closer
  const double inset = 2 * kDrawStep;
  p.walls = nlohmann::json::array({wall("wall_left", at, across, around->hi + inset, left_end - inset, thickness, yaw),
                                   wall("wall_right", at, across, right_end + inset, around->lo - inset, thickness, yaw)});
  return p;
}

}  // namespace

nlohmann::json generate_narrow_passage(GeneratorCase& c) {
  const GeneratorOptions options(c.options, c.family,
                                 {"dof", "link_length", "link_radius", "gap_width", "wall_length", "wall_thickness",
                                  "clearance", "block_pinv", "waypoints", "speed", "dt", "time_law"});
  const PlanarArmOptions arm_options = read_planar_arm_options(options, false);
  const double r = arm_options.link_radius;
  const Range gap_width = options.range("gap_width", {4 * r, 20 * r}, {2 * r + 1e-4, 10.0});
  const Range wall_length = options.range("wall_length", {0.2, 0.4}, {0.01, 2.0});
  const Range wall_thickness = options.range("wall_thickness", {0.03, 0.08}, {0.001, 1.0});
  const double clearance = options.number("clearance", 0.05, {0.0, 1.0});
  const bool block_pinv = read_block_pinv(options, c);
  const PathOptions path_options = read_path_options(options, {1, 3});
  if (c.options_only) return nullptr;
  Rng& rng = c.rng;
  for (int attempt = 0; attempt < kCaseAttempts; ++attempt) {
    const std::optional<WitnessedArm> drawn = draw_witnessed_arm(
        [&](Rng& r) { return draw_planar_arm(arm_options, r); }, path_options, TaskSpace::xy, rng);
    if (!drawn) continue;
    const GeneratedArm& arm = drawn->arm;
    const size_t samples = drawn->witness.hand.size();
    if (samples < 5) continue;
    std::optional<ArmSweep> pinv_sweep;
    if (block_pinv && !(pinv_sweep = minimum_norm_sweep(c, *drawn, TaskSpace::xy))) continue;
    std::optional<Passage> passage;
    for (int draw = 0; draw < kWallDraws && !passage; ++draw) {
      const size_t j = std::clamp(size_t(rng.uniform(kWallAtFrom, kWallAtTo) * double(samples - 1)), size_t(1), samples - 2);
      const double length = rounded(wall_length.draw(rng) * arm.reach);
      const double thickness = rounded(wall_thickness.draw(rng) * arm.reach);
      passage = passage_at(*drawn, j, length, thickness, clearance, gap_width);
      // the rule is the engine's measure, not the construction: clear of the
      // witness arm by the clearance, and both walls near it (they bound its gap)
      if (passage && (witness_clearance(drawn->sweep, passage->walls) <= clearance ||
                      obstacles_within(drawn->sweep, passage->walls, kWallsBound * clearance + kWallsRounding) < 2))
        passage.reset();
      // with block_pinv, only walls the minimum-norm solution's arm runs into
      if (passage && pinv_sweep && witness_clearance(*pinv_sweep, passage->walls) > 0) passage.reset();
    }
    if (!passage) continue;
    const std::string description =
        case_title(c) + ": " + arm.summary + "; the hand's trace crosses a gap " + fixed_digits(passage->gap, 4) +
        " m wide (" + fixed_digits(passage->gap / r, 1) + " link radii) between two walls " +
        fixed_digits(passage->thickness, 3) + " m thick, cut to the witness: every link of the witness arm stays more than " +
        fixed_digits(clearance, 3) + " m from them at every step; " +
        witness_summary(drawn->witness, int(drawn->path.configurations.size()) - 1) + ".";
    nlohmann::json doc = witnessed_document(c, description, *drawn, passage->walls, TaskSpace::xy, clearance);
    doc["witness"]["difficulty"]["gap_width"] = rounded(passage->gap, 1e-6);
    return doc;
  }
  no_case_found(c, "options.gap_width, options.wall_length, options.clearance or options.block_pinv");
}

}  // namespace rrlab

// Family moving_obstacles: a planar arm, its hand on a polyline through
// reachable waypoints, and obstacles moving at constant velocity across it.
//
// | option         | meaning                                              | default                     | unit    |
// |----------------|------------------------------------------------------|-----------------------------|---------|
// | dof            | joints (links) of the arm, [min, max] or a number    | [3, 12]                     | —       |
// | link_length    | each link's length, drawn per link                   | [0.2, 0.6]                  | m       |
// | link_radius    | every link's capsule radius                          | 0.02                        | m       |
// | obstacles      | obstacle count (the blocking ones among them)        | [2, 4]                      | —       |
// | obstacle_size  | sphere radius / box half-edge / polygon radius       | [0.04, 0.12]                | × reach |
// | shapes         | shapes drawn from (uniformly)                        | sphere, box, polygon, point | —       |
// | obstacle_speed | each obstacle's speed, its direction uniform         | [0.1, 0.3] × reach per second | m/s     |
// | clearance      | least distance from the witness arm at every step   | 0.05                   | m       |
// | blocking       | obstacles passing through pinv's arm, each met where no other is | 2          | —       |
// | block_pinv     | false: blocking 0                                    | true                        | —       |
// | waypoints      | waypoints after the start                            | [2, 4]                      | —       |
// | speed          | hand speed the witness is timed by                     | 0.2 × reach per second      | m/s     |
// | dt             | time step                                            | 0.01                        | s       |
// | time_law       | "quintic" (rest to rest) or "linear" (the witness) | quintic                       | —       |
//
// The first `blocking` pass, at some step, through the arm of the
// minimum-norm solution (generator_blocking.hpp); each other obstacle is
// aimed to pass through a random point of the hand's trace at a random time
// in [0.2, 0.9] of the run (not when the hand is there), so it crosses the
// path while the arm works. All keep the clearance from the witness arm at
// every step: the witness dodges every obstacle in time.
#include <algorithm>
#include <cmath>

#include <rrlab/generators/generator_arms.hpp>
#include <rrlab/generators/generator_blocking.hpp>
#include <rrlab/generators/generator_case.hpp>
#include <rrlab/generators/generator_clutter.hpp>
#include <rrlab/generators/generator_obstacles.hpp>
#include <rrlab/generators/generator_path.hpp>
#include <rrlab/generators/generator_witness.hpp>
#include <rrlab/scenario/scenario.hpp>

namespace rrlab {

namespace {

constexpr double kCrossFrom = 0.2, kCrossTo = 0.9;  // fractions of the duration
constexpr double kDefaultSpeedMin = 0.1, kDefaultSpeedMax = 0.3;  // reaches per second

}  // namespace

nlohmann::json generate_moving_obstacles(GeneratorCase& c) {
  const GeneratorOptions options(c.options, c.family,
                                 {"dof", "link_length", "link_radius", "obstacles", "obstacle_size", "shapes",
                                  "obstacle_speed", "clearance", "blocking", "block_pinv", "waypoints", "speed", "dt",
                                  "time_law"});
  const PlanarArmOptions arm_options = read_planar_arm_options(options, false);
  const ClutterOptions clutter =
      read_clutter_options(options, {2, 4}, {"sphere", "box", "polygon", "point"}, read_blocking(options, c));
  if (clutter.count.min < 1) throw ScenarioError("options.obstacles", "must be at least 1 in this family");
  const bool speed_given = options.has("obstacle_speed");
  const Range given_speed = options.range("obstacle_speed", {}, {0.001, 100.0});
  const PathOptions path_options = read_path_options(options);
  if (c.options_only) return nullptr;
  Rng& rng = c.rng;
  for (int attempt = 0; attempt < kCaseAttempts; ++attempt) {
    const std::optional<WitnessedArm> drawn = draw_witnessed_arm(
        [&](Rng& r) { return draw_planar_arm(arm_options, r); }, path_options, TaskSpace::xy, rng);
    if (!drawn) continue;
    const GeneratedArm& arm = drawn->arm;
    const KeepOut keep_out{&drawn->sweep, clutter.clearance};
    std::optional<ArmSweep> pinv_sweep;
    if (clutter.blocking.max > 0 && !(pinv_sweep = minimum_norm_sweep(c, *drawn, TaskSpace::xy))) continue;
    const Range speed_range =
        speed_given ? given_speed : Range{kDefaultSpeedMin * arm.reach, kDefaultSpeedMax * arm.reach};
    const double duration = drawn->witness.duration;
    const auto velocity_of = [&](Rng& r) {
      const double speed = speed_range.draw(r), heading = r.uniform(-M_PI, M_PI);
      return Eigen::Vector3d(rounded(speed * std::cos(heading)), rounded(speed * std::sin(heading)), 0);
    };
    const auto moving = [&](const std::string& shape, const Eigen::Vector3d& start, const Eigen::Vector3d& velocity,
                            double size, int k, Rng& r) {
      nlohmann::json o = draw_obstacle(shape, start, size, false, k + 1, r);
      o["velocity"] = {velocity.x(), velocity.y()};
      return o;
    };
    const int count = clutter.count.draw(rng);
    const int blocking = pinv_sweep ? clutter.blocking.draw(rng) : 0;
    nlohmann::json obstacles = nlohmann::json::array();
    if (blocking > 0) {
      // each passes, at its anchor's step, through pinv's arm there (where
      // pinv strays from the witness): pinv, which ignores obstacles, runs into it
      PinvBlockers blockers(*pinv_sweep, drawn->sweep, clutter.clearance);
      const std::optional<nlohmann::json> on_pinv = place_blockers(
          blocking, blockers, keep_out,
          [&](const BlockAnchor& anchor, int k, Rng& r) -> std::optional<nlohmann::json> {
            const std::string& shape = clutter.shapes[r.below(clutter.shapes.size())];
            const Eigen::Vector3d velocity = velocity_of(r);
            const std::optional<PinvBlockers::Fit> fit =
                blockers.fit(anchor, velocity, shape, false, scaled(clutter.size, arm.reach), r);
            if (!fit) return std::nullopt;
            return moving(shape, fit->centre - velocity * anchor.t, velocity, fit->size, k, r);
          },
          rng);
      if (!on_pinv) continue;
      obstacles = *on_pinv;
    }
    // the others are aimed through a point of the hand's trace at 0.2-0.9 of the run
    const std::optional<nlohmann::json> crossing = place_obstacles(
        count - blocking, keep_out,
        [&](int k, Rng& r) -> std::optional<nlohmann::json> {
          const double size = clutter.size.draw(r) * arm.reach;
          const Eigen::Vector3d velocity = velocity_of(r);
          const Eigen::Vector3d through = point_along(drawn->path, r.uniform());
          const Eigen::Vector3d start = through - velocity * (r.uniform(kCrossFrom, kCrossTo) * duration);
          const std::string& shape = clutter.shapes[r.below(clutter.shapes.size())];
          return moving(shape, start, velocity, size, blocking + k, r);
        },
        rng);
    if (!crossing) continue;
    for (const nlohmann::json& o : *crossing) obstacles.push_back(o);
    const std::string description =
        case_title(c) + ": " + arm.summary + " and " + obstacle_summary(obstacles) + " moving at " +
        fixed_digits(speed_range.min, 3) + "-" + fixed_digits(speed_range.max, 3) + " m/s" +
        blocking_summary(blocking, "obstacle", "the first ") + "; " + (blocking > 0 ? "the others " : "each ") +
        "aimed through a point of the hand's trace at 0.2-0.9 of the run, all more than " +
        fixed_digits(clutter.clearance, 3) + " m from every link of the witness arm at every step; " +
        witness_summary(drawn->witness, int(drawn->path.configurations.size()) - 1) + ".";
    return witnessed_document(c, description, *drawn, obstacles, TaskSpace::xy, clutter.clearance);
  }
  no_case_found(c, "options.obstacles, options.obstacle_size, options.clearance or options.blocking");
}

}  // namespace rrlab

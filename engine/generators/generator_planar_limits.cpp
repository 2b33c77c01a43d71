// Family planar_limits: a planar arm with symmetric joint limits and a path
// along which the plain minimum-norm solution (pinv) drives a joint past its
// limit, checked by simulating pinv on every candidate.
//
// | option        | meaning                                              | default                 | unit    |
// |---------------|------------------------------------------------------|-------------------------|---------|
// | dof           | joints (links) of the arm, [min, max] or a number    | [3, 12]                 | —       |
// | link_length   | each link's length, drawn per link                   | [0.2, 0.6]              | m       |
// | link_radius   | every link's capsule radius                          | 0.02                    | m       |
// | limit_deg     | each joint's limits are +-this, drawn per joint      | [60, 150]               | deg     |
// | obstacles     | obstacle count                                       | 0                       | —       |
// | obstacle_size | sphere radius / box half-edge / polygon radius       | [0.04, 0.12]            | × reach |
// | shapes        | shapes drawn from (uniformly)                        | sphere, box, polygon, point | —   |
// | clearance     | least distance from the witness arm, every step | 0.05                    | m       |
// | waypoints     | waypoints after the start                            | [2, 4]                  | —       |
// | speed         | hand speed the witness is timed by                     | 0.2 × reach per second  | m/s     |
// | dt            | time step                                            | 0.01                    | s       |
// | time_law      | "quintic" (rest to rest) or "linear" (the witness) | quintic                   | —       |
//
// The start and every waypoint configuration are drawn within 0.9 of the
// limits, so the witness between them keeps inside; a candidate is kept
// only when a pinv run of it leaves the limits (at most kCaseAttempts
// candidates, drawn from the case's stream: deterministic).
#include <cmath>

#include <rrlab/generators/generator_arms.hpp>
#include <rrlab/generators/generator_case.hpp>
#include <rrlab/generators/generator_clutter.hpp>
#include <rrlab/generators/generator_path.hpp>
#include <rrlab/generators/generator_witness.hpp>
#include <rrlab/scenario/scenario.hpp>
#include <rrlab/sim/simulator.hpp>

namespace rrlab {

namespace {

struct LimitCrossing {
  int joint = -1;  // 0-based
  double t = 0;    // s
};

// Where a pinv run of `doc` first leaves the joint limits, if it does.
std::optional<LimitCrossing> pinv_limit_crossing(const nlohmann::json& doc) {
  Simulator sim(parse_scenario(doc), "pinv");
  const JointLimits& limits = sim.model().limits;
  const auto crossing = [&](const Eigen::VectorXd& q, double t) -> std::optional<LimitCrossing> {
    for (Eigen::Index i = 0; i < q.size(); ++i)
      if (q[i] < limits.lower[i] || q[i] > limits.upper[i]) return LimitCrossing{int(i), t};
    return std::nullopt;
  };
  while (!sim.done()) {
    sim.step();
    if (auto found = crossing(sim.frame().q, sim.frame().t)) return found;
  }
  return crossing(sim.state().q, sim.state().t);  // the state after the last step
}

}  // namespace

nlohmann::json generate_planar_limits(GeneratorCase& c) {
  const GeneratorOptions options(c.options, c.family,
                                 {"dof", "link_length", "link_radius", "limit_deg", "obstacles", "obstacle_size",
                                  "shapes", "clearance", "waypoints", "speed", "dt", "time_law"});
  const PlanarArmOptions arm_options = read_planar_arm_options(options, true);
  const ClutterOptions clutter = read_clutter_options(options, {0, 0}, {"sphere", "box", "polygon", "point"});
  const PathOptions path_options = read_path_options(options);
  if (c.options_only) return nullptr;
  Rng& rng = c.rng;
  for (int attempt = 0; attempt < kCaseAttempts; ++attempt) {
    const std::optional<WitnessedArm> drawn = draw_witnessed_arm(
        [&](Rng& r) { return draw_planar_arm(arm_options, r); }, path_options, TaskSpace::xy, rng);
    if (!drawn) continue;
    const std::optional<nlohmann::json> obstacles = place_clutter(clutter, *drawn, false, rng);
    if (!obstacles) continue;
    nlohmann::json doc = witnessed_document(c, "", *drawn, *obstacles, TaskSpace::xy, clutter.clearance);
    const std::optional<LimitCrossing> crossing = pinv_limit_crossing(doc);
    if (!crossing) continue;
    std::string description = case_title(c) + ": " + drawn->arm.summary + "; " +
                              witness_summary(drawn->witness, int(drawn->path.configurations.size()) - 1) +
                              "; the witness keeps " + fixed_digits(drawn->witness.limit_margin * 180.0 / M_PI, 1) +
                              " deg inside the limits, and pinv drives joint " + std::to_string(crossing->joint + 1) +
                              " past its limit at t = " + fixed_digits(crossing->t, 2) +
                              " s (checked by simulation, candidate " + std::to_string(attempt + 1) + ")";
    if (!obstacles->empty())
      description += "; " + obstacle_summary(*obstacles) + ", each more than " + fixed_digits(clutter.clearance, 3) +
                     " m from every link of the witness arm at every step";
    doc["description"] = description + ".";
    return doc;
  }
  no_case_found(c, "options.limit_deg, options.waypoints or options.obstacles");
}

}  // namespace rrlab

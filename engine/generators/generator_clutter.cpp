#include <rrlab/generators/generator_clutter.hpp>

#include <algorithm>
#include <limits>

#include <rrlab/collision/segment_geometry.hpp>
#include <rrlab/scenario/scenario.hpp>
#include <rrlab/sim/simulator.hpp>

namespace rrlab {

namespace {

constexpr double kNearWitness = 0.05;  // reaches: farther out than the clearance, at most

}  // namespace

std::optional<ArmSweep> minimum_norm_sweep(const GeneratorCase& c, const WitnessedArm& drawn, TaskSpace space) {
  Simulator sim(parse_scenario(witnessed_document(c, "", drawn, nlohmann::json::array(), space)), "pinv");
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
  const size_t keep = std::max<size_t>(1, by_distance.size() / 10);
  std::partial_sort(by_distance.begin(), by_distance.begin() + long(keep), by_distance.end());
  std::vector<size_t> out;
  for (size_t i = 0; i < keep && i < by_distance.size(); ++i) out.push_back(by_distance[i].second);
  std::sort(out.begin(), out.end());
  return out;
}

std::optional<nlohmann::json> ball_on_pinv(const ArmSweep& pinv, const ArmSweep& witness, double clearance, Range radius,
                                           Rng& rng, int candidates) {
  const std::vector<size_t> straying = straying_capsules(pinv, witness);
  if (straying.empty()) return std::nullopt;
  // room for a ball at c: the witness arm's least distance from c over every
  // step (a linear scan: cheaper for a point than sweep_clearance's ordering)
  const auto room_at = [&](const Eigen::Vector3d& c) {
    double least = std::numeric_limits<double>::infinity();
    for (const CapsuleSegment& s : witness.capsules)
      least = std::min(least, (collision::closest_point_on_segment(s.a, s.b, c) - c).norm() - s.radius);
    return least - clearance;
  };
  double best = -1;
  Eigen::Vector3d best_centre = Eigen::Vector3d::Zero();
  for (int k = 0; k < candidates; ++k) {
    const CapsuleSegment& link = pinv.capsules[straying[rng.below(straying.size())]];
    Eigen::Vector3d centre = link.a + rng.uniform() * (link.b - link.a);
    for (int i = 0; i < 3; ++i) centre[i] = rounded(centre[i], 1e-4);
    const double room = room_at(centre);
    if (room > best) best = room, best_centre = centre;
  }
  if (best < radius.min) return std::nullopt;
  const double r = rounded(std::min(best, radius.max) - 1e-4, 1e-4);
  if (r < radius.min) return std::nullopt;
  return nlohmann::json{{"id", "ball"},
                        {"shape", "sphere"},
                        {"center", {best_centre.x(), best_centre.y(), best_centre.z()}},
                        {"radius", r}};
}

std::optional<nlohmann::json> place_clutter(const ClutterOptions& clutter, const WitnessedArm& drawn, bool spatial,
                                            Rng& rng, const ArmSweep* blocking) {
  const KeepOut keep_out{&drawn.sweep, clutter.clearance};
  const GeneratedArm& arm = drawn.arm;
  const Eigen::Vector3d base = arm.model.base.translation();
  const std::vector<size_t> straying = blocking ? straying_capsules(*blocking, drawn.sweep) : std::vector<size_t>{};
  const auto draw = [&](int k, Rng& r) -> std::optional<nlohmann::json> {
    const std::string& shape = clutter.shapes[r.below(clutter.shapes.size())];
    const double size = clutter.size.draw(r) * arm.reach;
    Eigen::Vector3d center;
    if (k == 0 && blocking) {
      // on the axis of one of pinv's links at some step (among the tenth that
      // strays farthest from the witness): pinv, which ignores obstacles, runs into it
      const CapsuleSegment& link = blocking->capsules[straying[r.below(straying.size())]];
      center = link.a + r.uniform() * (link.b - link.a);
    } else if (k % 2 == 0) {
      // beside the witness arm: a point of one of its links at some step,
      // then out by the link's radius, the obstacle's size and 1-2 clearances
      const CapsuleSegment& link = drawn.sweep.capsules[r.below(drawn.sweep.capsules.size())];
      const Eigen::Vector3d on_link = link.a + r.uniform() * (link.b - link.a);
      Eigen::Vector3d away = point_in_ball(Eigen::Vector3d::Zero(), 1.0, spatial, r);
      if (away.norm() < 1e-6) return std::nullopt;
      away.normalize();
      center = on_link + (link.radius + size + clutter.clearance * (1.0 + r.uniform()) + kNearWitness * arm.reach * r.uniform()) * away;
    } else {
      center = point_in_ball(base, arm.reach, spatial, r);
    }
    return draw_obstacle(shape, center, size, spatial, k + 1, r);
  };
  return place_obstacles(clutter.count.draw(rng), keep_out, draw, rng);
}

nlohmann::json generate_clutter_case(GeneratorCase& c, const ClutterOptions& clutter, const PathOptions& path_options,
                                     const std::function<GeneratedArm(Rng&)>& draw_arm, bool spatial,
                                     TaskSpace space) {
  Rng& rng = c.rng;
  for (int attempt = 0; attempt < kCaseAttempts; ++attempt) {
    const std::optional<WitnessedArm> drawn = draw_witnessed_arm(draw_arm, path_options, space, rng);
    if (!drawn) continue;
    std::optional<ArmSweep> pinv_sweep;
    if (clutter.block_pinv && !(pinv_sweep = minimum_norm_sweep(c, *drawn, space))) continue;
    const std::optional<nlohmann::json> obstacles =
        place_clutter(clutter, *drawn, spatial, rng, pinv_sweep ? &*pinv_sweep : nullptr);
    if (!obstacles) continue;
    const std::string description =
        case_title(c) + ": " + drawn->arm.summary + " among " + obstacle_summary(*obstacles) + ", each more than " +
        fixed_digits(clutter.clearance, 3) + " m from every link of the witness arm at every step" +
        (clutter.block_pinv ? std::string(", the first where the arm of the minimum-norm solution (pinv) passes") : "") +
        "; " +
        witness_summary(drawn->witness, int(drawn->path.configurations.size()) - 1) + ".";
    return witnessed_document(c, description, *drawn, *obstacles, space);
  }
  no_case_found(c, "options.obstacles, options.obstacle_size, options.clearance or options.block_pinv");
}

}  // namespace rrlab

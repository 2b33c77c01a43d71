#include <rrlab/generators/generator_clutter.hpp>

#include <rrlab/scenario/scenario.hpp>

namespace rrlab {

namespace {

constexpr double kNearWitness = 0.05;  // reaches: farther out than the clearance, at most

}  // namespace

std::string blocking_summary(int blocking, const std::string& noun, const std::string& lead) {
  if (blocking == 0) return "";
  const std::string what = blocking == 1 ? (lead.empty() ? "a " : lead) + noun : lead + std::to_string(blocking) + " " + noun + "s";
  return ", " + what + " meeting the arm of the minimum-norm solution (pinv) at some step, each where no other does";
}

std::optional<nlohmann::json> place_clutter(const ClutterOptions& clutter, const WitnessedArm& drawn, bool spatial,
                                            Rng& rng, PinvBlockers* blockers) {
  const KeepOut keep_out{&drawn.sweep, clutter.clearance};
  const GeneratedArm& arm = drawn.arm;
  const Eigen::Vector3d base = arm.model.base.translation();
  const int count = clutter.count.draw(rng);
  const int blocking = blockers ? clutter.blocking.draw(rng) : 0;
  nlohmann::json placed = nlohmann::json::array();
  if (blocking > 0) {
    // on the axis of one of pinv's links at some step: pinv, which ignores
    // obstacles, runs into it
    const std::optional<nlohmann::json> on_pinv = place_blockers(
        blocking, *blockers, keep_out,
        [&](const BlockAnchor& anchor, int k, Rng& r) -> std::optional<nlohmann::json> {
          const std::string& shape = clutter.shapes[r.below(clutter.shapes.size())];
          const std::optional<PinvBlockers::Fit> fit =
              blockers->fit(anchor, Eigen::Vector3d::Zero(), shape, spatial, scaled(clutter.size, arm.reach), r);
          if (!fit) return std::nullopt;
          return draw_obstacle(shape, fit->centre, fit->size, spatial, k + 1, r);
        },
        rng);
    if (!on_pinv) return std::nullopt;
    placed = *on_pinv;
  }
  const auto draw = [&](int k, Rng& r) -> std::optional<nlohmann::json> {
    const std::string& shape = clutter.shapes[r.below(clutter.shapes.size())];
    const double size = clutter.size.draw(r) * arm.reach;
    Eigen::Vector3d center;
    if (k % 2 == 0) {
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
    return draw_obstacle(shape, center, size, spatial, blocking + k + 1, r);
  };
  const std::optional<nlohmann::json> rest = place_obstacles(std::max(0, count - blocking), keep_out, draw, rng);
  if (!rest) return std::nullopt;
  for (const nlohmann::json& o : *rest) placed.push_back(o);
  return placed;
}

nlohmann::json generate_clutter_case(GeneratorCase& c, const ClutterOptions& clutter, const PathOptions& path_options,
                                     const std::function<GeneratedArm(Rng&)>& draw_arm, bool spatial,
                                     TaskSpace space) {
  Rng& rng = c.rng;
  for (int attempt = 0; attempt < kCaseAttempts; ++attempt) {
    const std::optional<WitnessedArm> drawn = draw_witnessed_arm(draw_arm, path_options, space, rng);
    if (!drawn) continue;
    std::optional<ArmSweep> pinv_sweep;
    if (clutter.blocking.max > 0 && !(pinv_sweep = minimum_norm_sweep(c, *drawn, space))) continue;
    std::optional<PinvBlockers> blockers;
    if (pinv_sweep) blockers.emplace(*pinv_sweep, drawn->sweep, clutter.clearance);
    const std::optional<nlohmann::json> obstacles = place_clutter(clutter, *drawn, spatial, rng, blockers ? &*blockers : nullptr);
    if (!obstacles) continue;
    const int blocking = blockers ? int(blockers->anchors().size()) : 0;
    const std::string description =
        case_title(c) + ": " + drawn->arm.summary + " among " + obstacle_summary(*obstacles) + ", each more than " +
        fixed_digits(clutter.clearance, 3) + " m from every link of the witness arm at every step" +
        blocking_summary(blocking, "obstacle", "the first ") + "; " +
        witness_summary(drawn->witness, int(drawn->path.configurations.size()) - 1) + ".";
    return witnessed_document(c, description, *drawn, *obstacles, space, clutter.clearance);
  }
  no_case_found(c, "options.obstacles, options.obstacle_size, options.clearance or options.blocking");
}

}  // namespace rrlab

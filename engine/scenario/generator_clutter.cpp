#include "scenario/generator_clutter.hpp"

namespace rrlab {

namespace {

constexpr double kNearPath = 0.25;  // reaches

}  // namespace

std::optional<nlohmann::json> place_clutter(const ClutterOptions& clutter, const WitnessedArm& drawn, bool spatial,
                                            Rng& rng) {
  const KeepOut keep_out{&drawn.sweep, clutter.clearance};
  const GeneratedArm& arm = drawn.arm;
  const Eigen::Vector3d base = arm.model.base.translation();
  const auto draw = [&](int k, Rng& r) -> std::optional<nlohmann::json> {
    const Eigen::Vector3d center =
        k % 2 == 0 ? point_in_ball(point_along(drawn.path, r.uniform()), kNearPath * arm.reach, spatial, r)
                   : point_in_ball(base, arm.reach, spatial, r);
    const std::string& shape = clutter.shapes[r.below(clutter.shapes.size())];
    return draw_obstacle(shape, center, clutter.size.draw(r) * arm.reach, spatial, k + 1, r);
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
    const std::optional<nlohmann::json> obstacles = place_clutter(clutter, *drawn, spatial, rng);
    if (!obstacles) continue;
    const std::string description =
        case_title(c) + ": " + drawn->arm.summary + " among " + obstacle_summary(*obstacles) + ", each more than " +
        fixed_digits(clutter.clearance, 3) + " m from every link of the witness arm at every step; " +
        witness_summary(drawn->witness, int(drawn->path.configurations.size()) - 1) + ".";
    return witnessed_document(c, description, *drawn, *obstacles, space);
  }
  no_case_found(c, "options.obstacles, options.obstacle_size or options.clearance");
}

}  // namespace rrlab

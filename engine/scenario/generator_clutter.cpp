#include "scenario/generator_clutter.hpp"

namespace rrlab {

namespace {

constexpr double kNearPath = 0.25;  // reaches

}  // namespace

std::optional<nlohmann::json> place_clutter(const ClutterOptions& clutter, const GeneratedArm& arm,
                                            const GeneratedPath& path, bool spatial, Rng& rng) {
  const KeepOut keep_out{arm_capsules(arm.model, path.configurations[0]), clutter.clearance,
                         path_capsules(path.points, arm.link_radius)};
  const Eigen::Vector3d base = arm.model.base.translation();
  const auto draw = [&](int k, Rng& r) -> std::optional<nlohmann::json> {
    const Eigen::Vector3d center = k % 2 == 0
                                       ? point_in_ball(point_along(path, r.uniform()), kNearPath * arm.reach, spatial, r)
                                       : point_in_ball(base, arm.reach, spatial, r);
    const std::string& shape = clutter.shapes[r.below(clutter.shapes.size())];
    return draw_obstacle(shape, center, clutter.size.draw(r) * arm.reach, spatial, k + 1, r);
  };
  return place_obstacles(clutter.count.draw(rng), keep_out, draw, rng);
}

}  // namespace rrlab

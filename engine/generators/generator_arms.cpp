#include <rrlab/generators/generator_arms.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

#include <rrlab/generators/generator_case.hpp>
#include <rrlab/scenario/scenario.hpp>

namespace rrlab {

namespace {

constexpr double kDeg = M_PI / 180.0;
// Drawn configurations keep off the limits by this fraction of each range,
// so a start is strictly inside and a waypoint configuration is not at a stop.
constexpr double kLimitInset = 0.9;
// Planar arms without limits: the first joint turns freely, the others bend
// at most this much, which keeps drawn arms from folding onto themselves.
constexpr double kFreeBend = M_PI / 2;

// KUKA LBR iiwa 14 (standard DH): d per link, alpha signs, limits (deg).
constexpr double kIiwaD[7] = {0.36, 0, 0.42, 0, 0.40, 0, 0.126};
constexpr double kIiwaLimitDeg[7] = {170, 120, 170, 120, 170, 120, 175};

nlohmann::json angles_json(const Eigen::VectorXd& v) {
  nlohmann::json out = nlohmann::json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) out.push_back(v[i]);
  return out;
}

}  // namespace

PlanarArmOptions read_planar_arm_options(const GeneratorOptions& options, bool with_limits) {
  PlanarArmOptions o;
  o.dof = options.int_range("dof", o.dof, {3, 64});
  o.link_length = options.range("link_length", o.link_length, {0.01, 10.0});
  o.link_radius = options.number("link_radius", o.link_radius, {0.0, 0.5});
  if (o.link_radius >= 0.5 * o.link_length.min)
    throw ScenarioError("options.link_radius", "must be below half the shortest link length (" +
                                                   fixed_digits(0.5 * o.link_length.min, 4) + " m)");
  if (with_limits) o.limit_deg = options.range("limit_deg", {60, 150}, {10, 180});
  return o;
}

DhArmOptions read_dh_arm_options(const GeneratorOptions& options) {
  DhArmOptions o;
  o.length_scale = options.range("length_scale", o.length_scale, {0.25, 4.0});
  o.a_offset = options.range("a_offset", o.a_offset, {-0.5, 0.5});
  o.link_radius = options.number("link_radius", o.link_radius, {0.0, 0.2});
  return o;
}

GeneratedArm draw_planar_arm(const PlanarArmOptions& options, Rng& rng) {
  GeneratedArm arm;
  const int dof = options.dof.draw(rng);
  std::vector<PlanarLinkSpec> specs;
  nlohmann::json links = nlohmann::json::array();
  double longest = 0, shortest = INFINITY;
  for (int i = 0; i < dof; ++i) {
    const double length = rounded(options.link_length.draw(rng));
    specs.push_back({length, options.link_radius});
    links.push_back({{"length", length}, {"radius", options.link_radius}});
    longest = std::max(longest, length);
    shortest = std::min(shortest, length);
  }
  arm.model = make_planar(specs, Eigen::Vector2d::Zero());
  arm.robot = {{"kind", "planar"}, {"base", {0, 0}}, {"links", links}};
  arm.reach = arm.model.reach();
  arm.link_radius = options.link_radius;
  arm.draw_lower = Eigen::VectorXd::Constant(dof, -kFreeBend);
  arm.draw_upper = Eigen::VectorXd::Constant(dof, kFreeBend);
  std::ostringstream summary;
  summary << "a planar arm with " << dof << " joints (links " << fixed_digits(shortest, 3) << "-" << fixed_digits(longest, 3)
          << " m, reach " << fixed_digits(arm.reach, 3) << " m, radius " << options.link_radius << " m";
  if (options.limit_deg) {
    Eigen::VectorXd upper(dof);
    for (int i = 0; i < dof; ++i) upper[i] = rounded(options.limit_deg->draw(rng) * kDeg);
    arm.model.limits.lower = -upper;
    arm.model.limits.upper = upper;
    arm.robot["limits"] = {{"lower", angles_json(-upper)}, {"upper", angles_json(upper)}};
    arm.draw_lower = -kLimitInset * upper;
    arm.draw_upper = kLimitInset * upper;
    summary << ", joint limits +-" << fixed_digits(upper.minCoeff() / kDeg, 0) << "-" << fixed_digits(upper.maxCoeff() / kDeg, 0)
            << " deg";
  } else {
    arm.draw_lower[0] = -M_PI;
    arm.draw_upper[0] = M_PI;
    arm.hole_radius = std::max(0.0, 2 * longest - arm.reach);
  }
  summary << ")";
  arm.summary = summary.str();
  return arm;
}

GeneratedArm draw_dh7_arm(const DhArmOptions& options, Rng& rng) {
  GeneratedArm arm;
  std::vector<DhLinkSpec> specs;
  nlohmann::json links = nlohmann::json::array();
  Eigen::VectorXd upper(7);
  std::string alphas;
  for (int i = 0; i < 7; ++i) {
    DhLinkSpec s;
    s.d = rounded(kIiwaD[i] * options.length_scale.draw(rng));
    s.a = rounded(options.a_offset.draw(rng));
    s.alpha = i == 6 ? 0.0 : (rng.below(2) == 0 ? -M_PI / 2 : M_PI / 2);
    s.radius = options.link_radius;
    specs.push_back(s);
    links.push_back({{"a", s.a}, {"alpha", s.alpha}, {"d", s.d}, {"radius", s.radius}});
    upper[i] = kIiwaLimitDeg[i] * kDeg;
    alphas += (alphas.empty() ? "" : ", ") + std::string(s.alpha > 0 ? "90" : s.alpha < 0 ? "-90" : "0");
  }
  arm.model = make_dh(specs, Eigen::Isometry3d::Identity());
  arm.model.limits.lower = -upper;
  arm.model.limits.upper = upper;
  arm.robot = {{"kind", "dh"},
               {"base", {0, 0, 0}},
               {"links", links},
               {"limits", {{"lower", angles_json(-upper)}, {"upper", angles_json(upper)}}}};
  arm.reach = arm.model.reach();
  arm.link_radius = options.link_radius;
  arm.draw_lower = -kLimitInset * upper;
  arm.draw_upper = kLimitInset * upper;
  std::ostringstream summary;
  summary << "a 7-DOF DH arm after the KUKA LBR iiwa (d = " << specs[0].d << ", " << specs[2].d << ", "
          << specs[4].d << ", " << specs[6].d << " m; a within " << fixed_digits(options.a_offset.min, 3) << ".."
          << fixed_digits(options.a_offset.max, 3) << " m; alpha = " << alphas << " deg; reach " << fixed_digits(arm.reach, 3)
          << " m, radius " << options.link_radius << " m, iiwa joint limits)";
  arm.summary = summary.str();
  return arm;
}

Eigen::VectorXd draw_configuration(const GeneratedArm& arm, Rng& rng) {
  Eigen::VectorXd q(arm.draw_lower.size());
  for (Eigen::Index i = 0; i < q.size(); ++i) q[i] = rounded(rng.uniform(arm.draw_lower[i], arm.draw_upper[i]));
  return q;
}

Eigen::VectorXd draw_configuration_near(const GeneratedArm& arm, const Eigen::VectorXd& from, double step, Rng& rng) {
  Eigen::VectorXd q(from.size());
  for (Eigen::Index i = 0; i < q.size(); ++i)
    q[i] = rounded(rng.uniform(std::max(arm.draw_lower[i], from[i] - step), std::min(arm.draw_upper[i], from[i] + step)));
  return q;
}

nlohmann::json robot_with_q0(const GeneratedArm& arm, const Eigen::VectorXd& q0) {
  nlohmann::json robot = arm.robot;
  robot["q0"] = angles_json(q0);
  return robot;
}

}  // namespace rrlab

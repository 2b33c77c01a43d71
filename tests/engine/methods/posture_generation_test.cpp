// Chen et al. (2002) posture generation: criteria and the paper's simulations.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "engine/sim_helpers.hpp"
#include "engine/test_models.hpp"
#include "methods/posture_generation_criteria.hpp"
#include "methods/registry.hpp"

namespace rrlab {
namespace {

const double kLimit = 135.0 * M_PI / 180.0;

test::RunResult run(const std::string& file, const std::string& method) {
  std::ifstream in(test::source_path("scenarios/" + file));
  nlohmann::json doc = nlohmann::json::parse(in);
  const nlohmann::json params = method == "posture_generation" ? doc["method"]["params"] : nlohmann::json::object();
  return test::run_scenario(doc, method, params);
}

// Largest |q_j| over the run for joints with a finite limit in the model.
double max_limited_joint(const test::RunResult& r, const Model& model) {
  double m = 0;
  for (const Frame& f : r.frames)
    for (int j = 0; j < f.q.size(); ++j)
      if (std::isfinite(model.limits.upper[j])) m = std::max(m, std::abs(f.q[j]));
  return m;
}

Model model_of(const std::string& file) { return load_scenario_file(test::source_path("scenarios/" + file)).model; }

TEST(ChenCriteria, ConeIsFlatOutsideAndItsSlopeIsTheDerivative) {
  const double phi = 0.6;
  EXPECT_FALSE(chen::cone(0.7, phi).active);
  EXPECT_EQ(chen::cone(0.7, phi).value, 1.0);
  for (double psi : {0.05, 0.2, 0.4, 0.55}) {
    const double h = 1e-6;
    const double fd = (chen::cone(psi + h, phi).value - chen::cone(psi - h, phi).value) / (2 * h);
    EXPECT_NEAR(chen::cone(psi, phi).slope, fd, 1e-5) << psi;
    EXPECT_GT(chen::cone(psi, phi).slope, chen::cone(psi + 0.05, phi).slope);  // steeper nearer the obstacle
  }
  // finite at Ψ = 0 and past a limit (Ψ < 0): the push stays on
  EXPECT_GT(chen::cone(0.0, phi).slope, 0.0);
  EXPECT_TRUE(std::isfinite(chen::cone(-0.1, phi).slope));
  EXPECT_NEAR(chen::cone(0.0, phi).value, 0.0, 1e-12);
}

TEST(ChenCriteria, IncludedAngleDerivativeMatchesRotation) {
  const Eigen::Vector3d b(1.0, 0.3, 0), axis(0, 0, 1);
  const double a0 = 0.2;
  auto u_at = [](double a) { return Eigen::Vector3d(2 * std::cos(a), 2 * std::sin(a), 0); };
  const Eigen::Vector3d u = u_at(a0), du = axis.cross(u);
  const chen::Angle angle = chen::included_angle(u, du, b);
  const double h = 1e-6;
  const double fd =
      (chen::included_angle(u_at(a0 + h), du, b).psi - chen::included_angle(u_at(a0 - h), du, b).psi) / (2 * h);
  EXPECT_NEAR(angle.dpsi, fd, 1e-6);
}

TEST(ChenCriteria, AdjacentAndElasticGradientsMatchFiniteDifferences) {
  const Eigen::Vector3d d(0.3, -0.2, 0), axis(0, 0, 1);
  auto u_at = [](double a) { return Eigen::Vector3d(1.5 * std::cos(a), 1.5 * std::sin(a), 0); };
  const double a0 = 0.4, h = 1e-6, eta = 2.0;  // ‖D̄‖ ≈ 1.33 < η
  // D̄ = u − D with D fixed
  const Eigen::Vector3d du = axis.cross(u_at(a0));
  const chen::Adjacent t = chen::adjacent_term(u_at(a0) - d, du, eta);
  ASSERT_TRUE(t.active);
  const double fd = (chen::adjacent_term(u_at(a0 + h) - d, du, eta).value -
                     chen::adjacent_term(u_at(a0 - h) - d, du, eta).value) / (2 * h);
  EXPECT_NEAR(t.grad, fd, 1e-5);
  const Eigen::Vector3d e(0.2, 1.0, 0);
  const chen::Elastic el = chen::elastic_term(u_at(a0), du, e);
  const double fde =
      (chen::elastic_term(u_at(a0 + h), du, e).value - chen::elastic_term(u_at(a0 - h), du, e).value) / (2 * h);
  EXPECT_NEAR(el.grad, fde, 1e-6);
}

TEST(ChenSim3, MinimumNormPassesTheLimitPostureGenerationKeepsEveryJointInside) {
  const std::string file = "18_chen_sim3_joint_limits.json";
  const Model model = model_of(file);
  const auto pinv = run(file, "pinv");
  const auto chen = run(file, "posture_generation");
  const double pinv_max = max_limited_joint(pinv, model), chen_max = max_limited_joint(chen, model);
  std::printf("[ Chen Sim 3 ] largest |bending joint|: pinv %.3f rad, posture_generation %.3f rad (limit %.3f); "
              "max tracking error pinv %.5f, posture_generation %.5f\n",
              pinv_max, chen_max, kLimit, pinv.summary.max_tracking_error, chen.summary.max_tracking_error);
  EXPECT_GE(pinv_max, 2.36);  // Fig. 8: a joint reaches or passes 2.36 rad
  EXPECT_TRUE(pinv.summary.joint_limit_violated);
  EXPECT_FALSE(chen.summary.joint_limit_violated);  // Fig. 9: every joint inside its limits
  EXPECT_LT(chen_max, kLimit);
  EXPECT_LT(chen.summary.max_tracking_error, 0.01);
  EXPECT_LT(chen.summary.final_tracking_error, 0.01);
}

TEST(ChenSim1, Planar12TracksWithoutCollisionOrLimit) {
  const std::string file = "16_chen_sim1_planar12.json";
  const auto chen = run(file, "posture_generation");
  const auto sr = run(file, "sr_task_priority");
  std::printf("[ Chen Sim 1 ] posture_generation: max tracking error %.5f, min distance %.4f, largest |q| %.3f rad; "
              "sr_task_priority min distance %.4f\n",
              chen.summary.max_tracking_error, chen.summary.min_distance, max_limited_joint(chen, model_of(file)),
              sr.summary.min_distance);
  EXPECT_FALSE(chen.summary.collided);
  EXPECT_GT(chen.summary.min_distance, 0.1);
  EXPECT_FALSE(chen.summary.joint_limit_violated);
  EXPECT_LT(chen.summary.max_tracking_error, 0.01);
  EXPECT_TRUE(sr.summary.collided);  // the closest-point baseline does not make it
}

TEST(ChenSim2, Spatial16ThroughTheWindow) {
  const std::string file = "17_chen_sim2_spatial16_window.json";
  const auto chen = run(file, "posture_generation");
  double azimuth = 0;  // the unlimited x joints (reported)
  for (const Frame& f : chen.frames)
    for (int j = 2; j < f.q.size(); j += 2) azimuth = std::max(azimuth, std::abs(f.q[j]));
  std::printf("[ Chen Sim 2 ] posture_generation: max tracking error %.5f, min distance %.4f, largest |bending "
              "joint| %.3f rad, largest |azimuth joint| %.3f rad\n",
              chen.summary.max_tracking_error, chen.summary.min_distance, max_limited_joint(chen, model_of(file)),
              azimuth);
  EXPECT_FALSE(chen.summary.collided);
  EXPECT_GT(chen.summary.min_distance, 0.03);  // measured 0.041 (links of radius 0.05)
  EXPECT_FALSE(chen.summary.joint_limit_violated);
  EXPECT_LT(chen.summary.max_tracking_error, 0.01);
  const auto plain = run(file, "pinv");
  std::printf("[ Chen Sim 2 ] pinv min distance %.4f\n", plain.summary.min_distance);
  EXPECT_TRUE(plain.summary.collided);  // the window is narrow enough to matter
}

TEST(PostureGenerationParams, ValidatedAndChangeable) {
  const Model model = make_planar({{1, 0}, {1, 0}, {1, 0}, {1, 0}}, {0, 0});
  auto method = find_method("posture_generation")->make({model, TaskSpace::xy, 0, 1});
  EXPECT_THROW(method->set_param("eta", 0.0), ParamError);
  EXPECT_THROW(method->set_param("influence_deg", 200), ParamError);
  EXPECT_THROW(method->set_param("elastic_first_link", 2), ParamError);
  method->set_param("omega", 0.5);
  EXPECT_EQ(method->param("omega"), 0.5);
  const auto& names = method->diagnostic_names();
  for (const char* n : {"Gamma1", "Gamma2", "Gamma3", "Gamma4", "gamma1", "gamma2", "constrained_link"})
    EXPECT_NE(std::find(names.begin(), names.end(), n), names.end()) << n;
}

}  // namespace
}  // namespace rrlab

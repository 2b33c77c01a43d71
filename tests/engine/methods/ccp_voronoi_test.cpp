// Sezgin et al. (1997) configuration control points: the paper's examples.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "engine/sim_helpers.hpp"
#include "engine/test_models.hpp"
#include "methods/registry.hpp"

namespace rrlab {
namespace {

constexpr double kDeg = M_PI / 180;

nlohmann::json scenario_json(const std::string& file) {
  std::ifstream in(test::source_path("scenarios/" + file));
  return nlohmann::json::parse(in);
}

test::RunResult run(const std::string& file, const nlohmann::json& params,
                    const std::string& method = "ccp_voronoi") {
  nlohmann::json doc = scenario_json(file);
  nlohmann::json merged = method == "ccp_voronoi" ? doc["method"]["params"] : nlohmann::json::object();
  for (auto& [k, v] : params.items()) merged[k] = v;
  return test::run_scenario(doc, method, merged);
}

// Ex1 on the L-shape (scenario 10): Table 1 and Figs. 3-4.
TEST(CcpVoronoiEx1, CcpAtJointTwoCollides) {
  const auto r = run("10_sezgin_ex1_lshape.json", {{"ccp_link", 2}, {"ccp_at", 0}});
  EXPECT_TRUE(r.summary.collided) << "min distance " << r.summary.min_distance;
}

TEST(CcpVoronoiEx1, CcpAtJointThreeAvoids) {
  const auto r = run("10_sezgin_ex1_lshape.json", {{"ccp_link", 3}, {"ccp_at", 0}});
  EXPECT_FALSE(r.summary.collided);
  EXPECT_GT(r.summary.min_distance, 0.02);
  EXPECT_LT(r.summary.max_tracking_error, 0.01);
  std::printf("[ Ex1 ] CCP at joint 3: min distance %.4f, max tracking error %.5f\n", r.summary.min_distance,
              r.summary.max_tracking_error);
}

TEST(CcpVoronoiEx1, CcpAtMiddleOfLinkThreeAvoids) {
  const auto r = run("10_sezgin_ex1_lshape.json", {{"ccp_link", 3}, {"ccp_at", 0.5}});
  EXPECT_FALSE(r.summary.collided);
  EXPECT_GT(r.summary.min_distance, 0.02);
}

TEST(CcpVoronoiEx1, TwoCcpsAtMiddlesOfLinksTwoAndThreeAvoid) {
  const auto r = run("10_sezgin_ex1_lshape.json",
                     {{"ccp_link", 2}, {"ccp_at", 0.5}, {"ccp2_link", 3}, {"ccp2_at", 0.5}});
  EXPECT_FALSE(r.summary.collided);
  EXPECT_GT(r.summary.min_distance, 0.02);
}

// NOT REPRODUCED (Sezgin et al., Fig. 4a): with CCPs at the middles of links 1
// and 2 the paper's arm collides with the L-shape; rrlab's avoids at lambda =
// 10 (min distance 0.024). Tried lambda 5..30: it collides for lambda <= 8,
// but then so does Fig. 4b's pair at links 2 and 3 (lambda 9 is the only value
// where 4a avoids and 4b collides, the reverse of the paper); obstacle 1 as
// well. This test asserts what rrlab does get, so a change shows.
TEST(CcpVoronoiEx1, TwoCcpsAtMiddlesOfLinksOneAndTwoAvoidUnlikeFig4a) {
  const auto r = run("10_sezgin_ex1_lshape.json",
                     {{"ccp_link", 1}, {"ccp_at", 0.5}, {"ccp2_link", 2}, {"ccp2_at", 0.5}});
  std::printf("[ Ex1 ] CCPs at the middles of links 1 and 2: collided %d, min distance %.4f\n",
              int(r.summary.collided), r.summary.min_distance);
  EXPECT_FALSE(r.summary.collided) << "the paper's Fig. 4a collides; rrlab avoided until now";
  EXPECT_GT(r.summary.min_distance, 0.0);
}

// Table 1 (deg, the paper's convention: from +y, clockwise) against the run,
// matched by the position along the path (the knots are not evenly spaced).
struct Knot {
  double t1, t2, t3;
};
const std::vector<Knot> kJoint2 = {{9.61, 116.70, 76.77},  {-23.89, 146.54, 39.68}, {-19.47, 159.41, 3.96},
                                   {-1.11, 149.43, -1.93}, {11.35, 139.38, -2.98},  {21.38, 129.86, -3.47},
                                   {30.18, 120.53, -3.87}, {38.35, 111.14, -4.28},  {46.23, 101.48, -4.74}};
const std::vector<Knot> kJoint3 = {
    {14.82, 112.70, 80.38}, {-3.90, 127.61, 62.18},   {-18.98, 142.38, 43.21}, {-19.58, 162.31, -1.74},
    {4.11, 158.30, -25.69}, {22.79, 152.45, -43.71},  {40.27, 145.31, -61.59}, {58.94, 134.98, -80.94},
    {81.04, 115.77, -101.26}, {102.51, 82.66, -110.34}, {108.51, 65.53, -102.07}, {111.75, 52.39, -90.23},
    {116.18, 37.02, -76.22}, {119.48, 22.32, -58.49}};
const std::vector<Knot> kMiddle3 = {
    {32.55, 133.82, 0.16},  {16.54, 110.77, 77.03}, {4.18, 123.75, 53.64},   {0.94, 134.91, 27.47},
    {8.80, 139.46, 2.62},   {21.45, 137.69, -16.69}, {34.58, 132.68, -32.41}, {47.82, 125.35, -46.53},
    {61.70, 115.08, -59.74}, {76.73, 100.10, -71.13}, {92.02, 78.83, -76.44}, {104.35, 55.10, -70.91},
    {112.13, 33.99, -55.51}};

double path_parameter(double x, double y) {  // along (0.5, 0.5) -> (2.5, -0.2)
  const double dx = 2.0, dy = -0.7;
  return ((x - 0.5) * dx + (y - 0.5) * dy) / (dx * dx + dy * dy);
}

// Largest |Δq| (deg) per knot; prints the table.
std::vector<double> compare_with_table(const char* label, const std::vector<Knot>& knots,
                                       const test::RunResult& r) {
  std::vector<double> diffs;
  std::printf("[ Table 1 ] %s (project convention q = [90 - t1, -t2, -t3] deg)\n", label);
  for (size_t k = 0; k < knots.size(); ++k) {
    const std::vector<double> q = {(90 - knots[k].t1) * kDeg, -knots[k].t2 * kDeg, -knots[k].t3 * kDeg};
    const std::vector<double> tip = test::planar_tip(1.0, q);
    const double s = path_parameter(tip[0], tip[1] + 1.0);
    size_t best = 0;
    double best_gap = 1e9;
    for (size_t i = 0; i < r.frames.size(); ++i) {
      const double gap = std::abs(path_parameter(r.frames[i].ee_position.x(), r.frames[i].ee_position.y()) - s);
      if (gap < best_gap) best_gap = gap, best = i;
    }
    const Eigen::VectorXd& qs = r.frames[best].q;
    double worst = 0;
    for (int j = 0; j < 3; ++j) worst = std::max(worst, std::abs(std::remainder(qs[j] - q[j], 2 * M_PI)) / kDeg);
    diffs.push_back(worst);
    std::printf("  knot %2zu  s=%.3f  paper (%7.2f %7.2f %7.2f)  run (%7.2f %7.2f %7.2f)  max|dq| %6.2f\n", k + 1,
                s, q[0] / kDeg, q[1] / kDeg, q[2] / kDeg, qs[0] / kDeg, qs[1] / kDeg, qs[2] / kDeg, worst);
  }
  return diffs;
}

TEST(CcpVoronoiEx1, Table1CcpAtJointTwo) {
  const auto r = run("10_sezgin_ex1_lshape.json", {{"ccp_link", 2}, {"ccp_at", 0}});
  const auto d = compare_with_table("one CCP at joint 2", kJoint2, r);
  for (double v : d) EXPECT_LT(v, 3.0);  // measured: 2.7 deg at most
}

TEST(CcpVoronoiEx1, Table1CcpAtJointThree) {
  const auto r = run("10_sezgin_ex1_lshape.json", {{"ccp_link", 3}, {"ccp_at", 0}});
  const auto d = compare_with_table("one CCP at joint 3", kJoint3, r);
  // Knots 1-7 (the approach, up to s = 0.44) within 3.5 deg (measured 3.49
  // at knot 3); after the CCP's nearest vertex changes the run turns less
  // sharply than the paper's (knots 8-11 differ by up to 26 deg, 12-14 by
  // 1-9 deg), reported, not asserted.
  for (size_t k = 0; k < 7; ++k) EXPECT_LT(d[k], 3.5) << "knot " << k + 1;
}

TEST(CcpVoronoiEx1, Table1CcpAtMiddleOfLinkThree) {
  const auto r = run("10_sezgin_ex1_lshape.json", {{"ccp_link", 3}, {"ccp_at", 0.5}});
  const auto d = compare_with_table("one CCP at the middle of link 3", kMiddle3, r);
  // Knot 1 as printed (s = 0.32, third joint 0.16 deg) is out of sequence
  // with knots 2-13 (s = 0.08 ... 1.0): a transcription error in the paper.
  double sum = 0;
  for (size_t k = 1; k < d.size(); ++k) sum += d[k];
  std::printf("  mean max|dq| over knots 2-13: %.2f deg\n", sum / double(d.size() - 1));
  EXPECT_FALSE(r.summary.collided);
}

TEST(CcpVoronoiEx1Box, JointTwoCollidesJointThreeAvoids) {
  EXPECT_TRUE(run("11_sezgin_ex1_box.json", {{"ccp_link", 2}, {"ccp_at", 0}}).summary.collided);
  EXPECT_FALSE(run("11_sezgin_ex1_box.json", {{"ccp_link", 3}, {"ccp_at", 0}}).summary.collided);
}

// The position method (eq. 6-7) solves for the stationary point of DI on the
// self-motion at every step; its first step climbs to a maximum (the paper's
// "initial conditions ... by the Lagrangian multiplier method").
TEST(CcpVoronoiEx1, LagrangianPositionMethodTracksAndAvoids) {
  const std::vector<nlohmann::json> variants = {
      {{"ccp_link", 2}, {"ccp_at", 0}},
      {{"ccp_link", 3}, {"ccp_at", 0}},
      {{"ccp_link", 3}, {"ccp_at", 0.5}},
      {{"ccp_link", 2}, {"ccp_at", 0.5}, {"ccp2_link", 3}, {"ccp2_at", 0.5}}};
  for (nlohmann::json params : variants) {
    params["integrator"] = "lagrangian";
    const auto r = run("10_sezgin_ex1_lshape.json", params);
    int converged = 0;  // diagnostic 6: newton_iterations (-1: not converged, fallback step)
    for (const Frame& f : r.frames) converged += f.diagnostics[6] >= 0;
    std::printf("[ Ex1 lagrangian ] %s: collided %d, min distance %.4f, max tracking error %.5f, Newton "
                "converged in %d of %zu steps\n",
                params.dump().c_str(), int(r.summary.collided), r.summary.min_distance,
                r.summary.max_tracking_error, converged, r.frames.size());
    EXPECT_FALSE(r.summary.collided) << params.dump();
    EXPECT_LT(r.summary.max_tracking_error, 0.005) << params.dump();
    EXPECT_GE(converged, int(0.85 * double(r.frames.size()))) << params.dump();
  }
}

TEST(CcpVoronoiEx1, NullSpaceMotionLeavesTheEndEffectorOnThePath) {
  // DI at lambda = 10 changes the configuration by up to ~100 deg, while the
  // end-effector stays on the line (RK4, closed-loop reference).
  const auto r = run("10_sezgin_ex1_lshape.json", {{"ccp_link", 3}, {"ccp_at", 0}});
  const auto plain = run("10_sezgin_ex1_lshape.json", {}, "pinv");
  EXPECT_LT(r.max_error_after(1), 0.01);
  EXPECT_GT((r.summary.final_q - plain.summary.final_q).cwiseAbs().maxCoeff(), 0.5);
}

TEST(CcpVoronoiEx2, MovingTriangleAndRectangleAvoided) {
  const auto r = run("12_sezgin_ex2_moving_triangle.json", {});
  EXPECT_FALSE(r.summary.collided);
  EXPECT_GT(r.summary.min_distance, 0.1);
  EXPECT_LT(r.summary.max_tracking_error, 0.01);
  std::printf("[ Ex2 ] DM: min distance %.4f, final tracking error %.5f\n", r.summary.min_distance,
              r.summary.final_tracking_error);
}

TEST(CcpVoronoiEx3, HybridPassesTheGapWhereDiAloneDoesNot) {
  const auto hybrid = run("13_sezgin_ex3_narrow_gap.json", {});
  const auto di = run("13_sezgin_ex3_narrow_gap.json", {{"mode", "DI"}});
  const auto dm = run("13_sezgin_ex3_narrow_gap.json", {{"mode", "DM"}});
  std::printf("[ Ex3 ] min distance: hybrid %.4f, DI %.4f, DM %.4f\n", hybrid.summary.min_distance,
              di.summary.min_distance, dm.summary.min_distance);
  EXPECT_FALSE(hybrid.summary.collided);
  EXPECT_LT(hybrid.summary.final_tracking_error, 0.02);
  EXPECT_TRUE(di.summary.collided);
  EXPECT_TRUE(dm.summary.collided);  // DM alone from the start also fails: the paper uses it only in the gap
  // the hybrid actually switched
  double dm_steps = 0;  // diagnostic 1: dm_active
  for (const Frame& f : hybrid.frames) dm_steps += f.diagnostics[1];
  EXPECT_GT(dm_steps, 0);
  EXPECT_LT(dm_steps, double(hybrid.frames.size()));
}

// Smallest distance from joints 2 and 3 to the wall's face x = 2.2 over a run.
double joint_clearance(const test::RunResult& r) {
  double m = 1e9;
  for (const Frame& f : r.frames) {
    const std::vector<double> j2 = test::planar_tip(1.0, {f.q[0]});
    const std::vector<double> j3 = test::planar_tip(1.0, {f.q[0], f.q[1]});
    m = std::min({m, 2.2 - j2[0], 2.2 - j3[0]});
  }
  return m;
}

TEST(CcpVoronoiEx4, LinksKeptAwayFromTheWall) {
  for (const char* file : {"14_sezgin_ex4_wall_bottom.json", "15_sezgin_ex4_wall_top.json"}) {
    const auto di = run(file, {});
    const auto plain = run(file, {}, "pinv");
    EXPECT_FALSE(di.summary.collided) << file;
    EXPECT_LT(di.summary.final_tracking_error, 0.02) << file;
    std::printf("[ Ex4 ] %s: joint clearance from the wall DI %.3f, pinv %.3f\n", file, joint_clearance(di),
                joint_clearance(plain));
    EXPECT_GT(joint_clearance(di), joint_clearance(plain)) << file;
  }
}

TEST(CcpVoronoiParams, CcpOnAMissingLinkIsRefused) {
  const Model model = make_planar({{1, 0}, {1, 0}, {1, 0}}, {0, 1});
  auto method = find_method("ccp_voronoi")->make({model, TaskSpace::xy, 1, 1});
  method->set_param("ccp_link", 2);
  EXPECT_THROW(method->set_param("ccp_link", 4), ParamError);
  EXPECT_EQ(method->param("ccp_link"), 2);
  EXPECT_THROW(method->set_param("ccp_at", 1.5), ParamError);
  EXPECT_THROW(method->set_param("mode", 3), ParamError);
  method->set_param("ccp2_link", 3);
  EXPECT_THROW(method->set_param("ccp2_link", 9), ParamError);
  EXPECT_EQ(method->param("ccp2_link"), 3);
}

TEST(CcpVoronoiParams, DeterministicRuns) {
  const auto a = run("12_sezgin_ex2_moving_triangle.json", {});
  const auto b = run("12_sezgin_ex2_moving_triangle.json", {});
  ASSERT_EQ(a.frames.size(), b.frames.size());
  for (size_t i = 0; i < a.frames.size(); ++i) ASSERT_EQ(a.frames[i].q, b.frames[i].q);
}

}  // namespace
}  // namespace rrlab

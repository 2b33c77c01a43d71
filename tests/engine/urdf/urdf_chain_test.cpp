// The three shipped URDF arms against forward kinematics written separately
// from the same published parameters, and the URDF faults that must be named.
#include <rrlab/urdf/urdf_chain.hpp>

#include <gtest/gtest.h>

#include <functional>
#include <random>

#include <rrlab/kinematics/kinematics.hpp>

#include "engine/test_models.hpp"

namespace rrlab {
namespace {

Model chain_model(const UrdfChain& chain) {
  Model m = make_chain(Eigen::Isometry3d::Identity(), chain.joints, chain.tip);
  m.limits = chain.limits;
  return m;
}

Eigen::Matrix4d rot_x(double a) {
  Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
  t.block<3, 3>(0, 0) = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()).toRotationMatrix();
  return t;
}
Eigen::Matrix4d rot_z(double a) {
  Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
  t.block<3, 3>(0, 0) = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return t;
}
Eigen::Matrix4d trans(double x, double y, double z) {
  Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
  t.block<3, 1>(0, 3) = Eigen::Vector3d(x, y, z);
  return t;
}

struct DhRow { double a, alpha, d, theta; };

// Standard DH, written out as matrices: T = base · Π Rz(θ_i + q_i) Tz(d_i) Tx(a_i) Rx(α_i).
Eigen::Matrix4d standard_dh(const std::vector<DhRow>& rows, const Eigen::Matrix4d& base, const Eigen::VectorXd& q) {
  Eigen::Matrix4d t = base;
  for (size_t i = 0; i < rows.size(); ++i) {
    const DhRow& r = rows[i];
    const double c = std::cos(r.theta + q[i]), s = std::sin(r.theta + q[i]);
    const double ca = std::cos(r.alpha), sa = std::sin(r.alpha);
    Eigen::Matrix4d a;
    a << c, -s * ca, s * sa, r.a * c,  //
        s, c * ca, -c * sa, r.a * s,   //
        0, sa, ca, r.d,                //
        0, 0, 0, 1;
    t = t * a;
  }
  return t;
}

// Modified (Craig) DH: T = Π Rx(α_{i-1}) Tx(a_{i-1}) Rz(q_i) Tz(d_i), then the flange.
Eigen::Matrix4d modified_dh(const std::vector<DhRow>& rows, const Eigen::VectorXd& q, double flange) {
  Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
  for (size_t i = 0; i < rows.size(); ++i) t = t * rot_x(rows[i].alpha) * trans(rows[i].a, 0, 0) * rot_z(q[i]) * trans(0, 0, rows[i].d);
  return t * trans(0, 0, flange);
}

// Largest position (m) and orientation (Frobenius norm of the rotation
// difference) errors over random configurations inside the limits.
std::pair<double, double> fk_error(const UrdfChain& chain, const std::function<Eigen::Matrix4d(const Eigen::VectorXd&)>& reference) {
  const Model model = chain_model(chain);
  KinematicsData kin(model);
  std::mt19937 rng(7);
  double pos = 0, rot = 0;
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd q(model.dof());
    for (int i = 0; i < model.dof(); ++i) {
      const double lo = std::isfinite(model.limits.lower[i]) ? model.limits.lower[i] : -M_PI;
      const double hi = std::isfinite(model.limits.upper[i]) ? model.limits.upper[i] : M_PI;
      q[i] = trial == 0 ? 0.0 : std::uniform_real_distribution<double>(lo, hi)(rng);
    }
    if (trial == 0) q = q.cwiseMax(model.limits.lower).cwiseMin(model.limits.upper);
    forward_kinematics(model, q, kin);
    const Eigen::Matrix4d want = reference(q);
    pos = std::max(pos, (kin.end_effector().translation() - want.block<3, 1>(0, 3)).norm());
    rot = std::max(rot, (kin.end_effector().linear() - want.block<3, 3>(0, 0)).norm());
  }
  return {pos, rot};
}

constexpr double kHalf = M_PI / 2;
constexpr double kDeg = M_PI / 180;

// KUKA LBR iiwa 14 R820 specification: standard DH d = 0.36, 0, 0.42, 0, 0.40, 0, 0.126 m.
TEST(UrdfArms, Iiwa14MatchesKukaDh) {
  const UrdfChain chain = read_urdf_chain(test::read_source_file("scenarios/robots/iiwa14.urdf"), "iiwa_link_0", "iiwa_tip");
  ASSERT_EQ(chain.joints.size(), 7u);
  const std::vector<DhRow> rows = {{0, -kHalf, 0.36, 0}, {0, kHalf, 0, 0}, {0, kHalf, 0.42, 0}, {0, -kHalf, 0, 0},
                                   {0, -kHalf, 0.40, 0}, {0, kHalf, 0, 0}, {0, 0, 0.126, 0}};
  const auto [pos, rot] = fk_error(chain, [&](const Eigen::VectorXd& q) { return standard_dh(rows, Eigen::Matrix4d::Identity(), q); });
  EXPECT_LT(pos, 1e-9);  // measured ~1e-16 (the URDF's rpy carry 10 digits)
  EXPECT_LT(rot, 1e-9);
  EXPECT_NEAR(chain.limits.upper[1], 120 * kDeg, 1e-9);
  EXPECT_NEAR(chain.limits.lower[6], -175 * kDeg, 1e-9);
  EXPECT_NEAR(chain.limits.velocity[3], 75 * kDeg, 1e-9);
}

// Franka FCI documentation: modified DH, flange d = 0.107 m.
TEST(UrdfArms, PandaMatchesFrankaModifiedDh) {
  const UrdfChain chain = read_urdf_chain(test::read_source_file("scenarios/robots/panda.urdf"), "panda_link_0", "panda_tip");
  ASSERT_EQ(chain.joints.size(), 7u);
  const std::vector<DhRow> rows = {{0, 0, 0.333, 0},          {0, -kHalf, 0, 0},       {0, kHalf, 0.316, 0},
                                   {0.0825, kHalf, 0, 0},     {-0.0825, -kHalf, 0.384, 0},
                                   {0, kHalf, 0, 0},          {0.088, kHalf, 0, 0}};
  const auto [pos, rot] = fk_error(chain, [&](const Eigen::VectorXd& q) { return modified_dh(rows, q, 0.107); });
  EXPECT_LT(pos, 1e-9);
  EXPECT_LT(rot, 1e-9);
  EXPECT_NEAR(chain.limits.lower[3], -3.0718, 1e-12);
  EXPECT_NEAR(chain.limits.upper[5], 3.7525, 1e-12);
  EXPECT_NEAR(chain.limits.velocity[6], 2.61, 1e-12);
}

// Kinova Gen3 user guide: classical DH with the base turned by π about x.
TEST(UrdfArms, Gen3MatchesKinovaDh) {
  const UrdfChain chain = read_urdf_chain(test::read_source_file("scenarios/robots/gen3.urdf"), "gen3_link_0", "gen3_tip");
  ASSERT_EQ(chain.joints.size(), 7u);
  const double pi = M_PI;
  const std::vector<DhRow> rows = {{0, kHalf, -(0.1564 + 0.1284), 0},  {0, kHalf, -(0.0054 + 0.0064), pi},
                                   {0, kHalf, -(0.2104 + 0.2104), pi}, {0, kHalf, -(0.0064 + 0.0064), pi},
                                   {0, kHalf, -(0.2084 + 0.1059), pi}, {0, kHalf, 0, pi},
                                   {0, pi, -(0.1059 + 0.0615), pi}};
  const auto [pos, rot] = fk_error(chain, [&](const Eigen::VectorXd& q) { return standard_dh(rows, rot_x(pi), q); });
  EXPECT_LT(pos, 1e-9);
  EXPECT_LT(rot, 1e-9);
  // continuous joints 1, 3, 5, 7 are unbounded
  EXPECT_TRUE(std::isinf(chain.limits.upper[0]));
  EXPECT_TRUE(std::isinf(chain.limits.lower[6]));
  EXPECT_NEAR(chain.limits.upper[1], 128.9 * kDeg, 1e-9);
  EXPECT_NEAR(chain.limits.velocity[4], 1.22, 1e-12);
}

// Capsule radii come from the collision cylinders.
TEST(UrdfArms, LinkRadiiFromCollisionCylinders) {
  const UrdfChain chain = read_urdf_chain(test::read_source_file("scenarios/robots/iiwa14.urdf"), "", "");
  EXPECT_EQ(chain.base_link, "iiwa_link_0");
  EXPECT_EQ(chain.tip_link, "iiwa_tip");
  EXPECT_DOUBLE_EQ(chain.joints[0].radius, 0.075);
  EXPECT_DOUBLE_EQ(chain.joints[6].radius, 0.05);
}

// A small chain for the error cases: base -j1-> l1 -j2-> l2 -fixed-> tip.
std::string small_urdf(const std::string& j2_extra = "", const std::string& j2_type = "revolute",
                       const std::string& j2_child = "l2", const std::string& extra = "") {
  return R"(<robot name="r"><link name="base"/><link name="l1"/><link name="l2"/><link name="tip"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><origin xyz="0 0 0.5" rpy="0 0 0"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" velocity="2" effort="1"/></joint>
  <joint name="j2" type=")" + j2_type + R"("><parent link="l1"/><child link=")" + j2_child + R"("/>
    <origin xyz="0.4 0 0" rpy="0 1.5707963 0"/><axis xyz="0 1 0"/><limit lower="-1" upper="1" velocity="2" effort="1"/>)" +
         j2_extra + R"(</joint>
  <joint name="jt" type="fixed"><parent link="l2"/><child link="tip"/><origin xyz="0.3 0 0"/></joint>)" + extra +
         "</robot>";
}

std::string error_of(const std::string& xml, const std::string& tip = "") {
  try {
    read_urdf_chain(xml, "", tip);
  } catch (const UrdfError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(UrdfChain, SmallChainFoldsTheFixedJointIntoTheTip) {
  const UrdfChain chain = read_urdf_chain(small_urdf(), "", "");
  ASSERT_EQ(chain.joints.size(), 2u);
  EXPECT_EQ(chain.joint_names[1], "j2");
  EXPECT_EQ(chain.tip_link, "tip");
  const Model model = chain_model(chain);
  KinematicsData kin(model);
  forward_kinematics(model, Eigen::Vector2d(M_PI / 2, 0), kin);
  // j1 turns l1 by 90° about z: j2 sits at (0, 0.4, 0.5); j2's origin pitches
  // by 90° about y, so the tip's +x (0.3 m) points along -z.
  EXPECT_LT((kin.end_effector().translation() - Eigen::Vector3d(0, 0.4, 0.2)).norm(), 1e-6);  // rpy to 7 digits
  EXPECT_LT((kin.link_start.col(1) - Eigen::Vector3d(0, 0.4, 0.5)).norm(), 1e-12);
}

TEST(UrdfChain, PrismaticAndContinuousJoints) {
  std::string xml = small_urdf("", "prismatic");
  const UrdfChain chain = read_urdf_chain(xml, "", "");
  EXPECT_EQ(chain.joints[1].type, JointType::prismatic);
  const Model model = chain_model(chain);
  KinematicsData kin(model);
  forward_kinematics(model, Eigen::Vector2d(0, 0.25), kin);  // slides 0.25 m along the joint's y
  EXPECT_LT((kin.end_effector().translation() - Eigen::Vector3d(0.4, 0.25, 0.2)).norm(), 1e-6);
  const UrdfChain cont = read_urdf_chain(small_urdf("", "continuous"), "", "");
  EXPECT_TRUE(std::isinf(cont.limits.upper[1]));
  EXPECT_DOUBLE_EQ(cont.limits.velocity[1], 2.0);
}

TEST(UrdfChain, FaultsAreNamed) {
  EXPECT_NE(error_of(small_urdf(R"(<mimic joint="j1" multiplier="1"/>)")).find("joint 'j2' is a mimic joint"), std::string::npos)
      << error_of(small_urdf(R"(<mimic joint="j1" multiplier="1"/>)"));
  EXPECT_NE(error_of(small_urdf("", "floating")).find("joint 'j2' is a floating joint"), std::string::npos);
  EXPECT_NE(error_of(small_urdf("", "revolute", "l9")).find("joint 'j2' names child link 'l9', which is not defined"),
            std::string::npos);
  // a cycle: l1 becomes a child of tip as well as of base
  const std::string cycle = small_urdf("", "revolute", "l2",
                                       R"(<joint name="back" type="fixed"><parent link="tip"/><child link="base"/></joint>)");
  EXPECT_NE(error_of(cycle).find("cycle"), std::string::npos) << error_of(cycle);
  const std::string two_parents = small_urdf("", "revolute", "l2",
                                             R"(<joint name="again" type="fixed"><parent link="base"/><child link="l2"/></joint>)");
  EXPECT_NE(error_of(two_parents).find("link 'l2' is the child of two joints ('j2' and 'again')"), std::string::npos);
  EXPECT_NE(error_of("<robot name='r'><link name='a'></robot>").find("malformed XML at line 1"), std::string::npos)
      << error_of("<robot name='r'><link name='a'></robot>");
  EXPECT_NE(error_of(small_urdf(), "nowhere").find("tip_link 'nowhere' is not a link"), std::string::npos);
  EXPECT_NE(error_of("<robot name='r'><link name='a'/></robot>").find("no revolute, continuous or prismatic joint"),
            std::string::npos);
}

TEST(UrdfChain, EmptyTextUrdfdomsReasonsAndTheKeyAtFault) {
  EXPECT_EQ(error_of(""), "the URDF is empty");
  EXPECT_EQ(error_of(" \n\t"), "the URDF is empty");
  // urdfdom logs why it refuses a document; the error quotes it (and nothing reaches stderr)
  std::string no_limit = small_urdf();
  no_limit.erase(no_limit.find("<limit"), no_limit.find("</joint>") - no_limit.find("<limit"));  // j1's
  EXPECT_EQ(error_of(no_limit),
            "urdfdom rejected the URDF: Joint [j1] is of type REVOLUTE but it does not specify limits; "
            "joint xml is not initialized correctly");
  std::string bad_number = small_urdf();
  bad_number.replace(bad_number.find("0.4 0 0"), 7, "0.4 abc 0");
  EXPECT_NE(error_of(bad_number).find("Unable to parse component [abc] to a double"), std::string::npos) << error_of(bad_number);
  EXPECT_NE(error_of(bad_number).find("Malformed parent origin element for joint [j2]"), std::string::npos);
  // base_link / tip_link faults say which key is at fault
  const auto key_of = [](const std::string& base, const std::string& tip) {
    try {
      read_urdf_chain(small_urdf(), base, tip);
    } catch (const UrdfError& e) {
      return e.key() + " | " + e.what();
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(key_of("pedestal", ""), "base_link | base_link 'pedestal' is not a link of the URDF");
  EXPECT_EQ(key_of("", "gripper"), "tip_link | tip_link 'gripper' is not a link of the URDF");
  EXPECT_EQ(key_of("l2", "l1"), "tip_link | tip_link 'l1' is not below base_link 'l2' (base_link must be an ancestor of tip_link)");
  EXPECT_EQ(key_of("l2", "tip"), " | no revolute, continuous or prismatic joint between 'l2' and 'tip'");
}

}  // namespace
}  // namespace rrlab

// The GA's closed-form planar arm and the AMSI path without directions
// against the general code they replace: kinematics, the damped Newton step
// and AMSI agree to rounding, also near singular configurations.
#include <rrlab/methods/multi_preview_planar.hpp>

#include <gtest/gtest.h>

#include <rrlab/methods/multi_preview_avoidance.hpp>
#include <rrlab/methods/multi_preview_ga.hpp>
#include <rrlab/util/right_inverse.hpp>

#include "engine/test_models.hpp"

namespace rrlab {
namespace {

TEST(PlanarArm, AppliesToPlanarChainsWithAnXyTaskOnly) {
  const Model planar = test::random_model(ModelKind::planar, 4, 1);
  EXPECT_TRUE(PlanarArm::applies(planar, TaskSpace::xy));
  EXPECT_FALSE(PlanarArm::applies(planar, TaskSpace::xyz));
  EXPECT_FALSE(PlanarArm::applies(test::random_model(ModelKind::spatial_xz, 4, 1), TaskSpace::xy));
  EXPECT_FALSE(PlanarArm::applies(test::random_model(ModelKind::dh, 4, 1), TaskSpace::xy));
  Model turned = planar;
  turned.base.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_FALSE(PlanarArm::applies(turned, TaskSpace::xy));
}

// Random configurations plus straight and folded arms (J Jᵀ singular or nearly so).
std::vector<Eigen::VectorXd> configurations(int n) {
  std::vector<Eigen::VectorXd> out;
  for (unsigned seed = 1; seed <= 40; ++seed) out.push_back(test::random_q(n, seed));
  out.push_back(Eigen::VectorXd::Zero(n));                       // straight: rank 1
  Eigen::VectorXd folded = Eigen::VectorXd::Zero(n);
  folded[1] = M_PI;                                               // folded back on itself
  out.push_back(folded);
  out.push_back(Eigen::VectorXd::Constant(n, 1e-7));              // nearly straight
  return out;
}

TEST(PlanarArm, KinematicsNewtonStepAndAmsiMatchTheGeneralCode) {
  for (int n : {2, 3, 4, 7}) {
    const Model model = test::random_model(ModelKind::planar, n, unsigned(n));
    PlanarArm arm(model);
    KinematicsData kin(model);
    Eigen::MatrixXd jacobian(2, n);
    RightInverse dls(2, n);
    AvoidanceManipulability general(model, TaskSpace::xy);  // with directions: the eigen-decomposition path
    std::vector<int> ranks;
    for (int i = 0; i < general.point_count(); ++i) ranks.push_back(general.ellipsoid(i).volume_rank);
    const Eigen::Vector3d target(0.3, -0.2, 0);
    for (const Eigen::VectorXd& q : configurations(n)) {
      forward_kinematics(model, q, kin);
      arm.kinematics(q);
      EXPECT_LT((arm.joints().back() - kin.end_effector().translation().head<2>()).norm(), 1e-13);
      task_jacobian(model, kin, TaskSpace::xy, jacobian);
      const double amsi = general.compute(model, kin, jacobian);
      EXPECT_NEAR(arm.amsi(ranks), amsi, 1e-7 * (1 + amsi)) << "n " << n << " q " << q.transpose();

      const Eigen::VectorXd error = target.head<2>() - kin.end_effector().translation().head<2>();
      EXPECT_NEAR(arm.hand_error(target), error.norm(), 1e-13);
      dls.factor_dls(jacobian, 1e-3);
      Eigen::VectorXd expected(n), step(n);
      dls.apply(error, expected);
      arm.newton_step(1e-3, step);
      EXPECT_LT((step - expected).norm(), 1e-9 * (1 + expected.norm())) << "n " << n;
    }
  }
}

// The GA's evaluator end to end: a planar arm (closed form, 2D distances)
// against the same arm with its base turned by 2π, which the closed form
// refuses (the rotation is not the identity bit for bit) and the general
// kinematics and collision world score: the same fitness, hand error and
// projected genes, also for genes that end inside the obstacles.
TEST(ImaginaryManipulator, PlanarClosedFormScoresAsTheGeneralPath) {
  const Model planar = make_planar({{0.5, 0.03}, {0.45, 0.02}, {0.4, 0.02}, {0.3, 0.01}}, {0.1, -0.2});
  Model general = planar;
  general.base.linear() = Eigen::AngleAxisd(2 * M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  ASSERT_TRUE(PlanarArm::applies(planar, TaskSpace::xy));
  ASSERT_FALSE(PlanarArm::applies(general, TaskSpace::xy));
  Scene scene;
  Obstacle wall;
  wall.id = "object";
  wall.shape = ShapeKind::polygon;
  wall.points = {{0.3, 0.3}, {1.2, 0.3}, {1.2, 0.5}, {0.6, 0.5}, {0.6, 1.1}, {0.3, 1.1}};
  scene.obstacles = {wall, test::moving_ball("ball", {-0.4, 0.6, 0.05}, 0.15, {0.05, 0, 0})};
  ImaginaryManipulator fast(planar, TaskSpace::xy), slow(general, TaskSpace::xy);
  for (ImaginaryManipulator* arm : {&fast, &slow}) {
    arm->set_scene(scene, 2.0);
    arm->set_potential(0.2, 10.0);
  }
  int touching = 0;
  for (unsigned seed = 1; seed <= 200; ++seed) {
    PreviewTarget target;
    const Eigen::VectorXd reach = test::random_q(2, seed + 1000);
    target.position = Eigen::Vector3d(0.1 + 0.8 * std::cos(reach[0]), -0.2 + 0.8 * std::sin(reach[0]), 0);
    Eigen::VectorXd a = test::random_q(4, seed), b = a;
    const Evaluation ea = fast.evaluate(a, target), eb = slow.evaluate(b, target);
    EXPECT_LT((a - b).norm(), 1e-9) << seed;
    EXPECT_NEAR(ea.residual, eb.residual, 1e-9) << seed;
    EXPECT_NEAR(ea.amsi, eb.amsi, 1e-7 * (1 + std::abs(eb.amsi))) << seed;
    EXPECT_NEAR(ea.potential, eb.potential, 1e-7 * (1 + std::abs(eb.potential))) << seed;
    EXPECT_NEAR(ea.fitness, eb.fitness, 1e-6 * (1 + std::abs(eb.fitness))) << seed;
    touching += eb.potential < 0;
  }
  EXPECT_GT(touching, 20) << "genes near and inside the obstacles must be among the cases";
}

TEST(AvoidanceManipulability, VolumesWithoutDirectionsMatchTheEigenDecomposition) {
  // the GA's evaluator on spatial arms: AMSI from principal minors
  for (ModelKind kind : {ModelKind::dh, ModelKind::urdf, ModelKind::spatial_xz, ModelKind::planar}) {
    for (TaskSpace space : {TaskSpace::xyz, TaskSpace::pose}) {
      const Model model = test::random_model(kind, 7, 3);
      if (kind == ModelKind::planar && space != TaskSpace::xyz) continue;
      const int n = model.dof();
      KinematicsData kin(model);
      Eigen::MatrixXd jacobian(task_rows(space), n);
      AvoidanceManipulability with(model, space, true), without(model, space, false);
      for (unsigned seed = 1; seed <= 20; ++seed) {
        forward_kinematics(model, test::random_q(n, seed), kin);
        task_jacobian(model, kin, space, jacobian);
        const double expected = with.compute(model, kin, jacobian);
        EXPECT_NEAR(without.compute(model, kin, jacobian), expected, 1e-9 * (1 + expected))
            << to_string(kind) << " " << to_string(space) << " seed " << seed;
      }
    }
  }
}

}  // namespace
}  // namespace rrlab

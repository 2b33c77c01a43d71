// The GA's closed-form planar arm and the AMSI path without directions
// against the general code they replace: kinematics, the damped Newton step
// and AMSI agree to rounding, also near singular configurations.
#include "methods/multi_preview_planar.hpp"

#include <gtest/gtest.h>

#include "engine/test_models.hpp"
#include "methods/multi_preview_avoidance.hpp"
#include "methods/multi_preview_ga.hpp"
#include "util/right_inverse.hpp"

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

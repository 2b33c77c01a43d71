// The kinematics entry points check what their caller hands them with
// RRLAB_CHECK (util/check.hpp): a wrong size or index is a clear
// std::invalid_argument in Release too, never a read past a buffer.
#include <rrlab/kinematics/kinematics.hpp>

#include <gtest/gtest.h>

#include <functional>
#include <stdexcept>
#include <string>

#include "engine/test_models.hpp"

namespace rrlab {
namespace {

// `call` throws std::invalid_argument whose message contains `words`.
void expect_input_error(const std::function<void()>& call, const std::string& words) {
  try {
    call();
    ADD_FAILURE() << "no exception; expected one saying \"" << words << "\"";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(KinematicsInput, WrongSizesAndIndicesAreClearErrors) {
  const Model model = test::random_model(ModelKind::planar, 4, 7);
  const Model other = test::random_model(ModelKind::planar, 6, 7);
  KinematicsData data(model), other_data(other);
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(4);
  forward_kinematics(model, q, data);  // the right sizes: no error

  expect_input_error([&] { forward_kinematics(model, Eigen::VectorXd::Zero(3), data); },
                     "q has 3 entries for a model of 4 joints");
  expect_input_error([&] { forward_kinematics_from(model, q, data, 5); }, "first joint 5 outside 0..4");
  expect_input_error([&] { forward_kinematics_from(model, q, data, -1); }, "first joint -1 outside");
  expect_input_error([&] { forward_kinematics(model, q, other_data); }, "KinematicsData was made for a model");

  Eigen::MatrixXd jac6(6, 4), jac3(3, 4), wrong(6, 3);
  const Eigen::Vector3d p = data.end_effector().translation();
  point_jacobian(model, data, 3, p, jac6);
  point_jacobian_linear(model, data, 3, p, jac3);
  expect_input_error([&] { point_jacobian(model, data, 3, p, wrong); }, "jac is 6 x 3, not 6 x 4");
  expect_input_error([&] { point_jacobian(model, data, 4, p, jac6); }, "link 4 outside 0..3");
  expect_input_error([&] { point_jacobian_linear(model, data, -1, p, jac3); }, "link -1 outside 0..3");
  expect_input_error([&] { point_jacobian_linear(model, data, 0, p, jac6); }, "jac is 6 x 4, not 3 x 4");

  Eigen::MatrixXd task(2, 4);
  task_jacobian(model, data, TaskSpace::xy, task);
  expect_input_error([&] { task_jacobian(model, data, TaskSpace::xyz, task); }, "jac is 2 x 4, not 3 x 4");
  const int columns[] = {1, 4};
  expect_input_error([&] { task_jacobian_columns(model, data, TaskSpace::xy, columns, 2, task); },
                     "column 4 outside 0..3");
  task_jacobian_columns(model, data, TaskSpace::xy, columns, 1, task);  // column 1 only: fine
}

}  // namespace
}  // namespace rrlab

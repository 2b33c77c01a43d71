// Models and scenarios shared by the engine tests.
#pragma once

#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include <rrlab/model/model.hpp>
#include <rrlab/scenario/scenario.hpp>

namespace rrlab::test {

// A random model of the given kind with `joints` joints (spatial_xz: rounded
// down to pairs), seeded.
inline Model random_model(ModelKind kind, int joints, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> length(0.2, 1.5), angle(-M_PI, M_PI), offset(-0.5, 0.5);
  switch (kind) {
    case ModelKind::planar: {
      std::vector<PlanarLinkSpec> links(joints);
      for (auto& l : links) l.length = length(rng);
      return make_planar(links, {offset(rng), offset(rng)});
    }
    case ModelKind::spatial_xz: {
      std::vector<PlanarLinkSpec> links(std::max(1, joints / 2));
      for (auto& l : links) l.length = length(rng);
      return make_spatial_xz(links, {offset(rng), offset(rng), offset(rng)});
    }
    case ModelKind::dh: {
      std::vector<DhLinkSpec> links(joints);
      std::bernoulli_distribution prismatic(0.2);
      for (auto& l : links) {
        l.a = offset(rng);
        l.alpha = angle(rng);
        l.d = offset(rng);
        l.theta = angle(rng);
        l.joint = prismatic(rng) ? JointType::prismatic : JointType::revolute;
      }
      Eigen::Isometry3d base = Eigen::Isometry3d::Identity();
      base.translation() = Eigen::Vector3d(offset(rng), offset(rng), offset(rng));
      base.linear() = Eigen::AngleAxisd(angle(rng), Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
      return make_dh(links, base);
    }
    case ModelKind::urdf: {  // a general chain: random origins and axes
      std::vector<ChainJointSpec> specs(joints);
      for (auto& j : specs) {
        j.origin.translation() = Eigen::Vector3d(offset(rng), offset(rng), length(rng) * 0.5);
        j.origin.linear() = Eigen::AngleAxisd(angle(rng), Eigen::Vector3d(offset(rng), offset(rng), 1).normalized()).toRotationMatrix();
        j.axis = Eigen::Vector3d(offset(rng), offset(rng), offset(rng) + 1.0).normalized();
      }
      Eigen::Isometry3d tip = Eigen::Isometry3d::Identity();
      tip.translation() = Eigen::Vector3d(0, 0, 0.2);
      return make_chain(Eigen::Isometry3d::Identity(), specs, tip);
    }
  }
  return {};
}

inline Eigen::VectorXd random_q(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  Eigen::VectorXd q(n);
  for (int i = 0; i < n; ++i) q[i] = angle(rng);
  return q;
}

// KUKA LBR iiwa 14-like 7-DOF DH chain (standard DH).
inline std::vector<DhLinkSpec> iiwa_dh() {
  const double h = M_PI / 2;
  return {{0, -h, 0.36, 0, 0.06}, {0, h, 0, 0, 0.06},  {0, h, 0.42, 0, 0.06}, {0, -h, 0, 0, 0.06},
          {0, -h, 0.40, 0, 0.05}, {0, h, 0, 0, 0.05},  {0, 0, 0.126, 0, 0.04}};
}

inline std::string source_path(const std::string& relative) {
  return std::string(RRLAB_SOURCE_DIR) + "/" + relative;
}

// The text of a file of the source tree (empty if it cannot be read).
inline std::string read_source_file(const std::string& relative) {
  std::ifstream in(source_path(relative));
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A ball obstacle at `centre` moving at `velocity`.
inline Obstacle moving_ball(const std::string& id, const Eigen::Vector3d& centre, double radius,
                            const Eigen::Vector3d& velocity) {
  Obstacle ball;
  ball.id = id;
  ball.shape = ShapeKind::sphere;
  ball.radius = radius;
  ball.position = ball.position0 = centre;
  ball.velocity = velocity;
  return ball;
}

}  // namespace rrlab::test
